// Stored results as `knoblab fits` and `knoblab results` show them: their
// key figures, their provenance, and the JSON record of one.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "knoblab/store/types.hpp"

namespace knoblab::cli {

// A positive id from the command line; UsageError "WHAT must be a NOUN id (a
// positive integer), got '…'" otherwise.
std::int64_t id_arg(const std::string& what, const std::string& noun, const std::string& text);

// The number at `keys` in a result, if there is one (an older fit, another
// model or a knob without detents may have none).
std::optional<double> number_at(const nlohmann::json& result, std::initializer_list<const char*> keys);

// "-" for a figure the result does not have; 'g' or 'f' notation.
std::string figure(std::optional<double> v, int precision, bool fixed);

// "-" for a result stored before provenance was kept (schema 7).
std::string version_of(const std::optional<store::Provenance>& p);
std::string short_sha256(const std::optional<store::Provenance>& p);  // first 12 hex digits

// One line of what a result found, presentation units stated:
// "rmse 0.1235 mN·m, 12.00 detents/rev"; "held-out rms 9.57 → 1.5 mN·m, 2 findings".
std::string fit_key_figure(const store::FitInfo& f);
std::string discrepancy_key_figure(const store::DiscrepancyInfo& d);

// The JSON record of a result (docs/store.md): kind, id, capture_id, when,
// provenance (null fields before schema 7), key figures in SI units, and the
// file count. `knoblab results --json` lists these.
nlohmann::json fit_record(const store::FitInfo& f);
nlohmann::json discrepancy_record(const store::DiscrepancyInfo& d);

}  // namespace knoblab::cli
