// What `fit` and `discrepancy` read and write: a capture from FILE.csv (or
// --input FILE.csv) or --capture ID --db FILE, and text to a file or stdout ('-').
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "args.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/interchange/capture.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::cli {

struct CaptureInput {
  interchange::Capture capture;
  std::string title;                       // file name, or "capture N (knob)"
  std::optional<store::Store> db;          // open when read from the store
  std::optional<std::int64_t> capture_id;
  // SHA-256 naming the input (docs/store.md): of the samples for a stored
  // capture (interchange::samples_sha256), of the file's bytes for a CSV.
  std::string sha256;
  std::string file;  // the CSV's path as given; empty for a stored capture
};

// Throws UsageError when neither or both sources are given.
CaptureInput read_capture_input(const Args& args);

// A second recording of the same knob from --heldout FILE.csv or
// --heldout-capture ID (--db); none when neither is given.
std::optional<CaptureInput> read_heldout_input(const Args& args);

// The data preparation --alpha, --no-filter and --linear ask for
// (UsageError otherwise).
fit::PrepOptions prep_options(const Args& args);

// --linear: the capture is a linear actuator's (fit/axis_units.hpp), as a
// CSV's '# axis: linear' line says.
inline const OptionSpec kLinearOption{
    "linear", false, "a linear axis: theta is a position in m, torque a force in N (text in mm, N, N/m); "
                     "as the CSV line '# axis: linear'"};

// Writes text and a newline to `path`, or to stdout when path is "-".
void write_text(const std::string& path, const std::string& text);

}  // namespace knoblab::cli
