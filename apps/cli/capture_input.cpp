#include "capture_input.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "knoblab/interchange/atomic_file.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/interchange/digest.hpp"
#include "store_open.hpp"

namespace knoblab::cli {

namespace {

// From the CSV `file` names, or the capture id under `id_key` in --db.
std::optional<CaptureInput> read_from(const Args& args, const std::optional<std::string>& file,
                                      const std::string& file_words, const std::string& id_key) {
  CaptureInput in;
  if (const auto& input = file) {
    if (args.has(id_key)) throw UsageError("give " + file_words + " or --" + id_key + ", not both");
    in.capture = interchange::read_csv(*input);
    in.title = std::filesystem::path(*input).filename().string();
    in.sha256 = interchange::file_sha256(*input);
    in.file = *input;
  } else if (auto id = args.get(id_key)) {
    in.db.emplace(open_store_to_add(args.require("db")));
    in.capture_id = parse_id("--" + id_key, *id);
    const auto info = in.db->capture_info(*in.capture_id);
    if (!info) throw std::runtime_error("no capture " + *id + " in the store");
    in.capture = in.db->load_samples(*in.capture_id);
    in.sha256 = interchange::samples_sha256(in.capture);
    in.title = "capture " + *id + (info->knob.empty() ? "" : " (" + info->knob + ")");
  } else {
    return std::nullopt;
  }
  // A metadata 'axis' the preparation would refuse, refused here naming the input.
  try {
    fit::capture_axis(in.capture);
  } catch (const fit::FitDataError& e) {
    throw fit::FitDataError((in.file.empty() ? in.title : in.file) + ": " + e.what());
  }
  return in;
}

}  // namespace

CaptureInput read_capture_input(const Args& args) {
  std::optional<CaptureInput> in = read_from(args, args.input(), "a FILE.csv", "capture");
  if (!in) throw UsageError("give a FILE.csv (or --input FILE.csv) or --capture ID --db FILE.sqlite");
  return std::move(*in);
}

std::optional<CaptureInput> read_heldout_input(const Args& args) {
  return read_from(args, args.get("heldout"), "--heldout", "heldout-capture");
}

fit::PrepOptions prep_options(const Args& args) {
  fit::PrepOptions prep;
  if (auto a = args.get("alpha")) {
    if (*a == "encoder") prep.alpha = fit::AlphaSource::Encoder;
    else if (*a == "accel") prep.alpha = fit::AlphaSource::Accelerometer;
    else throw UsageError("--alpha must be encoder or accel");
  }
  prep.filter = !args.has("no-filter");
  if (args.has("linear")) prep.axis = fit::Axis::Linear;
  return prep;
}

void write_text(const std::string& path, const std::string& text) {
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fputc('\n', stdout);
    return;
  }
  // A killed process or a full disk must not leave a half-written result in
  // place of the last good one (a truncated render model stops hapticd).
  interchange::write_file_atomically(path, text + "\n");
}

}  // namespace knoblab::cli
