#include "knob_file.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "knoblab/model/effect_json.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::cli {

namespace {

using nlohmann::json;

double number(const json& obj, const std::string& key, std::string_view where, double fallback) {
  if (!obj.contains(key)) return fallback;
  const json& v = obj.at(key);
  if (!v.is_number()) throw std::invalid_argument(std::string(where) + ": '" + key + "' is not a number");
  return v.get<double>();
}

void reject_unknown(const json& obj, const std::vector<std::string_view>& known, std::string_view where) {
  for (const auto& [key, value] : obj.items()) {
    bool ok = false;
    for (auto k : known) ok = ok || key == k;
    if (ok) continue;
    std::string list;
    for (auto k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    throw std::invalid_argument(std::string(where) + ": unknown parameter '" + key + "' (known: " + list + ")");
  }
}

// The knob of Eq. 6's eight parameters (fit order), without a stick band.
sim::KnobParams knob_from(const double (&v)[model::kThesisParamCount]) {
  const auto m = model::ThesisModel<double>::from_params(v);
  sim::KnobParams k;
  k.inertia = m.inertia;
  k.friction = m.friction;
  k.detents = m.detents;
  return k;
}

// The stick band's three values; the fit also writes how many samples it
// saw in the band, which describes the capture, not the knob.
model::KarnoppStick<double> stick_band(const json& s, const std::string& where) {
  reject_unknown(s, {"dv", "D_neg", "D_pos", "samples"}, where);
  return {number(s, "dv", where, 0.0), number(s, "D_neg", where, 0.0), number(s, "D_pos", where, 0.0)};
}

sim::KnobParams from_thesis6(const json& doc, const std::string& where) {
  const json& p = doc.at("params");
  std::vector<std::string_view> names(model::kThesisParamNames.begin(), model::kThesisParamNames.end());
  reject_unknown(p, names, where + ": params");
  double v[model::kThesisParamCount];
  for (std::size_t i = 0; i < model::kThesisParamCount; ++i) {
    const std::string key(model::kThesisParamNames[i]);
    v[i] = number(p, key, where, i == model::kP_pos ? 1.0 : 0.0);
  }
  sim::KnobParams k = knob_from(v);
  if (doc.contains("stick") && !doc.at("stick").is_null()) {
    if (!doc.at("stick").is_object()) throw std::invalid_argument(where + ": \"stick\" must be an object or null");
    k.stick = stick_band(doc.at("stick"), where + ": stick");
  }
  return k;
}

// Eq. 14: one symmetric viscous term and no Coulomb level; the stick band
// sits with the parameters, as hapticd's load_model takes them.
sim::KnobParams from_render4(const json& doc, const std::string& where) {
  const json& p = doc.at("params");
  reject_unknown(p, {"M_acc", "B_vel", "A_pos", "P_pos", "S_pos", "dv", "D_neg", "D_pos"}, where + ": params");
  const double B = number(p, "B_vel", where, 0.0);
  double v[model::kThesisParamCount] = {};
  v[model::kM_acc] = number(p, "M_acc", where, 0.0);
  v[model::kB_vel_neg] = B;
  v[model::kB_vel_pos] = B;
  v[model::kA_pos] = number(p, "A_pos", where, 0.0);
  v[model::kP_pos] = number(p, "P_pos", where, 1.0);
  v[model::kS_pos] = number(p, "S_pos", where, 0.0);
  sim::KnobParams k = knob_from(v);
  json band = json::object();
  for (const char* key : {"dv", "D_neg", "D_pos"})
    if (p.contains(key)) band[key] = p.at(key);
  k.stick = stick_band(band, where + ": params");
  return k;
}

// {"effect": ID, "params": {name: value}} each, under the names discrepancy
// reports (the effect table's), checked as --effects is.
std::vector<model::EffectSpec> effects_of(const json& list, const std::string& where) {
  if (!list.is_array()) throw std::invalid_argument(where + ": \"effects\" must be a list of {\"effect\": ID, \"params\": {…}}");
  std::vector<model::EffectSpec> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& e = list[i];
    const std::string at = where + ": effects[" + std::to_string(i) + "]";
    if (!e.is_object() || !e.contains("effect") || !e.at("effect").is_string() || !e.contains("params") ||
        !e.at("params").is_object())
      throw std::invalid_argument(at + ": expected {\"effect\": ID, \"params\": {…}}");
    try {
      out.push_back(model::effect_from_json(e.at("effect").get<std::string>(), e.at("params")));
    } catch (const std::invalid_argument& bad) {
      throw std::invalid_argument(at + ": " + bad.what());
    }
  }
  return out;
}

}  // namespace

KnobFile parse_knob_json(std::string_view text, std::string_view source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw std::invalid_argument(std::string(source) + ": not valid JSON: " + e.what());
  }
  const std::string where(source);
  if (!doc.is_object() || !doc.contains("params") || !doc.at("params").is_object())
    throw std::invalid_argument(where + ": expected an object with a \"params\" object");
  const std::string model = doc.contains("model") && doc.at("model").is_string() ? doc.at("model").get<std::string>()
                            : doc.contains("model")                              ? doc.at("model").dump()
                                                                                 : "thesis6";
  KnobFile file;
  if (model == "thesis6") file.knob = from_thesis6(doc, where);
  else if (model == "render4") file.knob = from_render4(doc, where);
  else throw std::invalid_argument(where + ": model '" + model + "' is neither 'thesis6' nor 'render4'");
  if (doc.contains("effects")) file.effects = effects_of(doc.at("effects"), where);
  return file;
}

KnobFile read_knob_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot open knob file " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parse_knob_json(text.str(), path.string());
}

}  // namespace knoblab::cli
