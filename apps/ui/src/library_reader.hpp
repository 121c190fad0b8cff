// The knob library as the UI shows it, read from the store read-only (it
// never writes and never waits for a writer): each capture with its knob,
// and the latest fit and discrepancy result stored for it. Qt-free, so it
// is tested on its own; KnobLibrary runs it off the UI thread.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace knoblab::ui {

struct LibraryEntry {
  std::int64_t capture_id = 0;
  std::string knob, status, started_at, stimulus, orientation, end_reason;
  std::string mounting;                                  // 'lab' | 'tripod'
  nlohmann::json metadata = nlohmann::json::object();    // gripper, notes, … as stored
  double rate_hz = 0.0;
  std::int64_t samples = 0;
  std::optional<std::int64_t> fit_id;
  nlohmann::json fit;  // the latest fit's result (docs/fit.md's JSON); null without one
  std::optional<std::int64_t> discrepancy_id;
  nlohmann::json discrepancy;  // the latest discrepancy result (docs/discrepancy.md); null without one
};

// Newest capture first. A store that does not exist yet is an empty
// library; one that cannot be read throws std::runtime_error saying why.
std::vector<LibraryEntry> read_library(const std::filesystem::path& db);

// One file stored with a result (`kind` "fit" or "discrepancy", its id): a
// report figure's CSV, for instance. Empty when there is no such file; throws
// std::runtime_error when the store cannot be read.
std::string read_result_file(const std::filesystem::path& db, const std::string& kind, std::int64_t id,
                             const std::string& name);

// An entry as the screens read it: SI values as stored, the fit's
// parameters with their 95 % intervals, the findings' names and sentences.
nlohmann::json entry_json(const LibraryEntry& e);

}  // namespace knoblab::ui
