#include "figure_args.hpp"

#include "knoblab/fit/plot/figure_files.hpp"

#include <algorithm>
#include <stdexcept>

namespace knoblab::cli {

std::vector<OptionSpec> with_figure_options(std::vector<OptionSpec> options, const std::string& dir_option) {
  const std::string dir = "--" + dir_option;
  options.push_back({"format", true, "figure files for " + dir + ": pdf,svg,png or any of them (default all three)"});
  options.push_back({"size", true,
                     "printed figure size for " + dir + ": WxH or a width alone, in mm, cm or in, e.g. "
                     "160x100mm (default 160 mm wide, each figure as tall as its panels need)"});
  options.push_back({"dpi", true, "PNG resolution for " + dir + " (default 300; PDF and SVG are vector)"});
  return options;
}

fit::plot::FigureOptions figure_options(const Args& args, const std::string& dir_option) {
  fit::plot::FigureOptions opt;
  for (const char* name : {"format", "size", "dpi"})
    if (args.has(name) && !args.has(dir_option))
      throw UsageError(std::string("--") + name + " needs --" + dir_option + " DIR");
  try {
    if (auto f = args.get("format")) opt.formats = fit::plot::parse_formats(*f);
    if (auto s = args.get("size")) fit::plot::parse_size(*s, opt);
    if (args.has("dpi")) opt.dpi = static_cast<int>(std::clamp<long long>(args.integer("dpi", opt.dpi), 0, 1 << 20));
    fit::plot::validate(opt);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (args.has(dir_option)) fit::plot::require_formats(opt.formats);
  return opt;
}

}  // namespace knoblab::cli
