#include "knoblab/hapticd/model_file.hpp"

#include <array>
#include <fstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "knoblab/model/effect_json.hpp"

namespace knoblab::hapticd {

namespace {

using nlohmann::json;

// What the renderer renders (load_model's "effects" keys), and why it does
// not render the rest of the library.
constexpr std::array<std::string_view, 8> kRendered = {"offset",       "gravity",  "spring",
                                                       "periodic_torque", "detent_shape", "stribeck",
                                                       "nonlinear_damping", "endstop"};
struct NotRendered {
  std::string_view id, why;
};
constexpr std::array<NotRendered, 7> kNotRendered = {{
    {"backlash", "play between the drive and the knob is lost motion with a state, not a torque of the knob's motion"},
    {"hysteresis", "Dahl presliding acts on the Coulomb level, which Eq. 14 folds into B_vel"},
    {"position_friction", "it modulates the Coulomb level, which Eq. 14 folds into B_vel; alone it would push the knob along"},
    {"drift", "friction changing over the recording's time is not a property of the knob"},
    {"time_delay", "a delay of the camera's torque channel, not the knob"},
    {"saturation", "the torque sensor's clipping, not the knob"},
    {"compliance", "the camera's gripper coupling, not the knob"},
}};

bool rendered(std::string_view id) {
  for (auto r : kRendered)
    if (r == id) return true;
  return false;
}

std::string known_ids() {
  std::string out;
  for (auto r : kRendered) out += (out.empty() ? "" : ", ") + std::string(r);
  for (const auto& n : kNotRendered) out += ", " + std::string(n.id);
  return out;
}

json effects_args(const json& list, const std::string& where) {
  if (!list.is_array()) throw ModelFileError(where + ": \"effects\" must be a list of {\"effect\": ID, \"params\": {…}}");
  json out = json::object();
  std::vector<std::string> refused;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& e = list[i];
    const std::string at = where + ": effects[" + std::to_string(i) + "]";
    if (!e.is_object() || !e.contains("effect") || !e.at("effect").is_string() || !e.contains("params") ||
        !e.at("params").is_object())
      throw ModelFileError(at + ": expected {\"effect\": ID, \"params\": {…}}");
    const std::string id = e.at("effect").get<std::string>();
    if (!rendered(id)) {
      bool known = false;
      for (const auto& n : kNotRendered) {
        if (n.id != id) continue;
        known = true;
        refused.push_back(id + " (" + std::string(n.why) + ")");
      }
      if (!known) throw ModelFileError(at + ": unknown effect '" + id + "' (known: " + known_ids() + ")");
      continue;
    }
    // Checked against the effect table as simulate checks it; the values
    // derived beside a parameter (cycles_per_rev, …) are dropped.
    json params;
    try {
      params = json::parse(model::effect_params_json(model::effect_from_json(id, e.at("params"))).dump());
    } catch (const std::invalid_argument& bad) {
      throw ModelFileError(at + ": " + bad.what());
    }
    if (id == "periodic_torque") {
      out[id].push_back(std::move(params));
    } else {
      if (out.contains(id)) throw ModelFileError(at + ": a second '" + id + "' (only periodic_torque may repeat)");
      out[id] = std::move(params);
    }
  }
  if (!refused.empty()) {
    std::string list_text;
    for (std::size_t i = 0; i < refused.size(); ++i)
      list_text += (i == 0 ? "" : i + 1 == refused.size() ? " and " : "; ") + refused[i];
    throw ModelFileError(where + ": hapticd cannot render " + list_text +
                         ". Remove " + (refused.size() == 1 ? "it" : "them") +
                         " from \"effects\" to render the rest of the model");
  }
  return out;
}

}  // namespace

json load_model_args(const json& file, const std::string& where) {
  if (!file.is_object() || !file.contains("model") || !file.at("model").is_string())
    throw ModelFileError(where + ": expected {\"model\": \"render4\", \"params\": {…}} (knoblab fit --render-model) "
                         "or a model file with a \"render\" object (knoblab discrepancy --model-out)");
  const std::string model = file.at("model").get<std::string>();
  json args;
  if (model == "render4") {
    if (!file.contains("params") || !file.at("params").is_object())
      throw ModelFileError(where + ": a render4 file needs a \"params\" object");
    args = file.at("params");
  } else if (file.contains("render")) {
    if (!file.at("render").is_object()) throw ModelFileError(where + ": \"render\" must be an object");
    args = file.at("render");
  } else if (model == "thesis6") {
    throw ModelFileError(where + ": a thesis6 model (a fit's result) has no render model: hapticd renders Eq. 14; "
                         "write one with knoblab fit --render-model, or use knoblab discrepancy --model-out");
  } else {
    throw ModelFileError(where + ": model '" + model + "' is neither 'render4' nor 'thesis6'");
  }
  if (file.contains("effects")) {
    json effects = effects_args(file.at("effects"), where);
    if (!effects.empty()) args["effects"] = std::move(effects);
  }
  return args;
}

json read_model_file_args(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw ModelFileError("cannot read model file " + path.string());
  json file;
  try {
    file = json::parse(in);
  } catch (const json::parse_error& e) {
    throw ModelFileError(path.string() + ": not JSON: " + e.what());
  }
  return load_model_args(file, path.string());
}

}  // namespace knoblab::hapticd
