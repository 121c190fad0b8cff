#include "knoblab/fit/knob_fit.hpp"

#include <stdexcept>

namespace knoblab::fit {

std::string_view model_name(ModelKind m) {
  return m == ModelKind::Thesis6 ? "thesis6" : "render4";
}

std::optional<ModelKind> parse_model(std::string_view name) {
  if (name == "thesis6") return ModelKind::Thesis6;
  if (name == "render4") return ModelKind::Render4;
  return std::nullopt;
}

std::vector<std::string_view> param_names(ModelKind m) {
  if (m == ModelKind::Thesis6) {
    return {model::kThesisParamNames.begin(), model::kThesisParamNames.end()};
  }
  return {"M_acc", "B_vel", "A_pos", "P_pos", "S_pos"};
}

std::size_t FitResult::index(std::string_view name) const {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return i;
  }
  throw std::out_of_range("no parameter named " + std::string(name) + " in a " +
                          std::string(model_name(model)) + " fit");
}

double FitResult::value(std::string_view name) const { return params.at(index(name)); }

}  // namespace knoblab::fit
