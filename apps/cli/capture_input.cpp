#include "capture_input.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "knoblab/interchange/csv.hpp"

namespace knoblab::cli {

CaptureInput read_capture_input(const Args& args) {
  CaptureInput in;
  if (auto input = args.get("input")) {
    if (args.has("capture")) throw UsageError("give --input or --capture, not both");
    in.capture = interchange::read_csv(*input);
    in.title = std::filesystem::path(*input).filename().string();
  } else if (auto id = args.get("capture")) {
    in.db.emplace(store::Store::open(args.require("db")));
    in.capture_id = std::stoll(*id);
    const auto info = in.db->capture_info(*in.capture_id);
    if (!info) throw std::runtime_error("no capture " + *id + " in the store");
    in.capture = in.db->load_samples(*in.capture_id);
    in.title = "capture " + *id + (info->knob.empty() ? "" : " (" + info->knob + ")");
  } else {
    throw UsageError("give --input FILE.csv or --capture ID --db FILE");
  }
  return in;
}

fit::PrepOptions prep_options(const Args& args) {
  fit::PrepOptions prep;
  if (auto a = args.get("alpha")) {
    if (*a == "encoder") prep.alpha = fit::AlphaSource::Encoder;
    else if (*a == "accel") prep.alpha = fit::AlphaSource::Accelerometer;
    else throw UsageError("--alpha must be encoder or accel");
  }
  prep.filter = !args.has("no-filter");
  return prep;
}

void write_text(const std::string& path, const std::string& text) {
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fputc('\n', stdout);
    return;
  }
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text << "\n";
  if (!f.flush()) throw std::runtime_error("cannot write " + path);
}

}  // namespace knoblab::cli
