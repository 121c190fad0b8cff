// knoblab: capture, import/export, convert and inspect knob recordings; the demo.
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "knoblab/fit/run_hooks.hpp"
#include "knoblab/version.hpp"

namespace knoblab::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> all = {
      {kSimulateSpec, run_simulate}, {kImportSpec, run_import}, {kExportSpec, run_export},
      {kListSpec, run_list},         {kConvertSpec, run_convert}, {kInspectSpec, run_inspect},
      {kFitSpec, run_fit},           {kFitsSpec, run_fits},       {kFitExportSpec, run_fit_export},
      {kDiscrepancySpec, run_discrepancy}, {kCompareSpec, run_compare}, {kResultsSpec, run_results},
      {kDemoSpec, run_demo}, {kCtlSpec, run_ctl}, {kStudySpec, run_study}, {kDesignSpec, run_design},
  };
  return all;
}

namespace {
void print_overview() {
  std::cout << "usage: knoblab COMMAND [OPTIONS]\n\ncommands:\n";
  for (const auto& c : commands()) {
    std::string name = "  " + c.spec.name;
    name.resize(14, ' ');
    std::cout << name << c.spec.summary.substr(0, c.spec.summary.find('\n')) << "\n";
  }
  std::cout << "\n'knoblab COMMAND --help' describes one command; 'knoblab --version' says which\n"
               "knoblab this is.\n";
}
}  // namespace

}  // namespace knoblab::cli

int main(int argc, char** argv) {
  using namespace knoblab::cli;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && args[0] == "--version") {
    std::cout << "knoblab " << knoblab::kVersion << "\n";
    return 0;
  }
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_overview();
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::cout << "knoblab " << knoblab::kVersion << "\n";
    return 0;
  }
  for (const auto& c : commands()) {
    if (c.spec.name != args[0]) continue;
    try {
      Args parsed(c.spec, std::vector<std::string>(args.begin() + 1, args.end()));
      if (parsed.help()) {
        std::cout << usage(c.spec);
        return 0;
      }
      if (parsed.version()) {
        std::cout << "knoblab " << knoblab::kVersion << "\n";
        return 0;
      }
      return c.run(parsed);
    } catch (const knoblab::fit::Cancelled&) {
      // Ctrl-C or SIGTERM (cancel.hpp): nothing was written or stored.
      std::cerr << "knoblab " << c.spec.name << ": cancelled\n";
      return 130;
    } catch (const UsageError& e) {
      std::cerr << "knoblab " << c.spec.name << ": " << e.what() << "\n"
                << "try 'knoblab " << c.spec.name << " --help'\n";
      return 2;
    } catch (const std::exception& e) {
      std::cerr << "knoblab " << c.spec.name << ": error: " << e.what() << "\n";
      return 1;
    }
  }
  std::cerr << "knoblab: unknown command '" << args[0] << "'; try 'knoblab --help'\n";
  return 2;
}
