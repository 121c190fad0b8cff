#include "provenance.hpp"

#include "knoblab/version.hpp"

namespace knoblab::cli {

store::Provenance provenance_of(const std::string& input_sha256, const nlohmann::json& options) {
  return {knoblab::kVersion, input_sha256, options.dump()};
}

nlohmann::json prep_options_json(const fit::PrepOptions& prep) {
  nlohmann::json j = {{"alpha", prep.alpha == fit::AlphaSource::Encoder ? "encoder" : "accel"},
                      {"filter", prep.filter}};
  if (prep.axis) j["axis"] = std::string(fit::axis_name(*prep.axis));  // --linear
  return j;
}

nlohmann::json fit_options_json(const fit::PrepOptions& prep, const fit::FitOptions& fit) {
  nlohmann::json j = prep_options_json(prep);
  j["model"] = std::string(fit::model_name(fit.model));
  j["detents"] = fit.detents == fit::FitOptions::Detents::Force  ? "yes"
                 : fit.detents == fit::FitOptions::Detents::None ? "no"
                                                                 : "auto";
  j["stick_band"] = fit.stick_band;
  return j;
}

nlohmann::json input_json(const CaptureInput& input) {
  nlohmann::json j = nlohmann::json::object();
  if (input.capture_id)
    j["capture"] = *input.capture_id;
  else
    j["file"] = input.file;
  j["sha256"] = input.sha256;
  return j;
}

}  // namespace knoblab::cli
