// What a stored result records about how it was made (docs/store.md): this
// knoblab's version, the digest of the capture it analysed, and the options
// it ran with, as a JSON object.
#pragma once

#include <nlohmann/json.hpp>

#include "capture_input.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/store/types.hpp"

namespace knoblab::cli {

// input_sha256: the analysed capture's interchange::samples_sha256.
store::Provenance provenance_of(const std::string& input_sha256, const nlohmann::json& options);

// The data preparation in a result's options: {"alpha": "accel"|"encoder", "filter": bool}.
nlohmann::json prep_options_json(const fit::PrepOptions& prep);
// A fit's: the preparation's and {"model", "detents": "auto"|"yes"|"no", "stick_band"}.
nlohmann::json fit_options_json(const fit::PrepOptions& prep, const fit::FitOptions& fit);

// An input named in a result's options (the held-out recording):
// {"capture": ID, "sha256": …} or {"file": PATH, "sha256": …}.
nlohmann::json input_json(const CaptureInput& input);

}  // namespace knoblab::cli
