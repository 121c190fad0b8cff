// Plain records the store takes and returns. JSON fields are strings the
// caller builds; the database checks them with json_valid.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "knoblab/interchange/sample.hpp"

namespace knoblab::store {

// One row of a capture (SI units); command is stored only when the capture
// was begun with has_command.
using interchange::Sample;

// What the caller says about a capture it records or imports.
struct NewCapture {
  std::string knob;                 // knob name, created if new; empty = no knob
  std::string mode = "lab";         // 'lab' | 'tripod'
  double rate_hz = 0;               // > 0; import: 0 = estimate from t
  std::string stimulus = "{}";      // JSON
  std::string orientation = "{}";   // JSON, e.g. axis tilt
  std::string calibration = "{}";   // JSON: C_cal, gravity A..D, torque offset, ...
  std::string source;               // 'simulate', 'hapticd', ...; import: empty = 'import'
  bool has_command = false;         // import: taken from the Capture instead
  std::string metadata;             // JSON object; empty = '{}' (import: the CSV's comments)
};

// A capture row as stored.
struct CaptureInfo {
  std::int64_t id = 0;
  std::optional<std::int64_t> knob_id;
  std::string knob;  // name, empty if none
  std::string mode;
  double rate_hz = 0;
  std::string stimulus, orientation, calibration, source;
  std::string status;  // 'recording' | 'complete' | 'incomplete'
  // Why an incomplete capture ended early or lost samples (e.g. "fault:
  // estop", "ring dropped 12 samples", "store busy"); none when it ended
  // normally (and for incomplete captures stored before schema version 5).
  std::optional<std::string> end_reason;
  std::optional<std::int64_t> writer_pid;
  bool has_command = false;
  std::string started_at;                  // ISO 8601 UTC
  std::optional<std::string> finished_at;  // ISO 8601 UTC
  std::int64_t sample_count = 0;           // committed samples
  std::string metadata;
};

// One sample of the biometrics box (thesis §4.4.1.2, 32 Hz), SI units.
struct BiometricSample {
  std::int64_t seq = 0;           // the box's sample counter
  double t = 0;                   // s, on the capture's clock
  double emg_corrugator = 0;      // V
  double emg_depressor = 0;       // V
  double skin_conductance = 0;    // S
};

struct KnobInfo {
  std::int64_t id = 0;
  std::string name, description, created_at;
};

// Where a stored result came from (schema 7); its created_at says when.
struct Provenance {
  std::string tool_version;    // the knoblab that made it (knoblab/version.hpp), not empty
  std::string input_sha256;    // 64 lowercase hex digits: the analysed capture's
                               // interchange::samples_sha256
  std::string options = "{}";  // JSON object: the options it ran with
};

struct FitInfo {
  std::int64_t id = 0;
  std::int64_t capture_id = 0;
  std::string model, params, result, created_at;
  std::optional<Provenance> provenance;  // none: stored before schema 7 or without one
  std::int64_t file_count = 0;           // report files stored with it
};

// A discrepancy run's result (docs/discrepancy.md's JSON) as stored.
struct DiscrepancyInfo {
  std::int64_t id = 0;
  std::int64_t capture_id = 0;
  // The capture held out whole (--heldout-capture); none when time blocks of
  // the capture itself were held out, the other recording came from a file,
  // or that capture has since been deleted.
  std::optional<std::int64_t> heldout_capture_id;
  std::string result;      // JSON, byte for byte as inserted
  std::string created_at;  // ISO 8601 UTC
  std::optional<Provenance> provenance;  // none: stored before schema 7 or without one
  std::int64_t file_count = 0;           // report files stored with it
};

// One file of a result's report (a plot, fit.json, the render model,
// summary.md), stored byte for byte. name is a plain file name: not empty,
// no '/', no NUL, not "." or "..", unique within its result.
struct ResultFile {
  std::string name;
  std::vector<std::uint8_t> bytes;
};
using FitFile = ResultFile;

struct ResultFileInfo {
  std::string name;
  std::int64_t size = 0;  // bytes
};
using FitFileInfo = ResultFileInfo;

}  // namespace knoblab::store
