// Effect specs to and from JSON (effect_json.hpp).
#include "knoblab/model/effect_json.hpp"

#include <stdexcept>

namespace knoblab::model {

nlohmann::ordered_json effect_params_json(const EffectSpec& spec) {
  nlohmann::ordered_json o = nlohmann::ordered_json::object();
  for (const auto& [name, value] : spec.params) o[name] = value;
  return o;
}

nlohmann::ordered_json effect_json(const EffectSpec& spec) {
  nlohmann::ordered_json o;
  o["effect"] = std::string(spec.id());
  o["params"] = effect_params_json(spec);
  return o;
}

EffectSpec effect_from_json(std::string_view id, const nlohmann::json& params) {
  const std::string where = "effect '" + std::string(id) + "': params";
  if (!params.is_object()) throw std::invalid_argument(where + " must be an object of numbers");
  NamedValues values;
  for (const auto& [name, value] : params.items()) {
    if (!value.is_number())
      throw std::invalid_argument(where + "." + name + " must be a number, not " + value.dump());
    values.emplace_back(name, value.get<double>());
  }
  return effect_from_params(id, values);
}

EffectSpec effect_from_json(const nlohmann::json& effect) {
  if (!effect.is_object() || !effect.contains("effect") || !effect["effect"].is_string())
    throw std::invalid_argument("an effect must be an object with \"effect\" (its id) and \"params\"");
  const std::string id = effect["effect"].get<std::string>();
  return effect_from_json(id, effect.contains("params") ? effect["params"] : nlohmann::json::object());
}

}  // namespace knoblab::model
