#include "knob_file.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

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

void reject_unknown(const json& obj, std::initializer_list<std::string_view> known, std::string_view where) {
  for (const auto& [key, value] : obj.items()) {
    bool ok = false;
    for (auto k : known) ok = ok || key == k;
    if (!ok) throw std::invalid_argument(std::string(where) + ": unknown parameter '" + key + "'");
  }
}

}  // namespace

sim::KnobParams parse_knob_json(std::string_view text, std::string_view source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw std::invalid_argument(std::string(source) + ": not valid JSON: " + e.what());
  }
  const std::string where(source);
  if (!doc.is_object() || !doc.contains("params") || !doc.at("params").is_object())
    throw std::invalid_argument(where + ": expected an object with a \"params\" object");
  if (doc.contains("model") && doc.at("model") != "thesis6")
    throw std::invalid_argument(where + ": model '" + doc.at("model").dump() + "' is not 'thesis6'");

  const json& p = doc.at("params");
  std::initializer_list<std::string_view> names = {"M_acc", "C_vel_neg", "B_vel_neg", "C_vel_pos",
                                                   "B_vel_pos", "A_pos", "P_pos", "S_pos"};
  reject_unknown(p, names, where + ": params");
  double v[model::kThesisParamCount];
  for (std::size_t i = 0; i < model::kThesisParamCount; ++i) {
    const std::string key(model::kThesisParamNames[i]);
    v[i] = number(p, key, where, i == model::kP_pos ? 1.0 : 0.0);
  }
  const auto m = model::ThesisModel<double>::from_params(v);
  sim::KnobParams k;
  k.inertia = m.inertia;
  k.friction = m.friction;
  k.detents = m.detents;
  if (doc.contains("stick")) {
    const json& s = doc.at("stick");
    if (!s.is_object()) throw std::invalid_argument(where + ": \"stick\" must be an object");
    reject_unknown(s, {"dv", "D_neg", "D_pos"}, where + ": stick");
    k.stick = {number(s, "dv", where, 0.0), number(s, "D_neg", where, 0.0), number(s, "D_pos", where, 0.0)};
  }
  return k;
}

sim::KnobParams read_knob_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot open knob file " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parse_knob_json(text.str(), path.string());
}

}  // namespace knoblab::cli
