#include "knoblab/sim/library_effects.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <vector>
#include <stdexcept>

#include "knoblab/model/effects.hpp"

namespace knoblab::sim {

namespace {

// Each effect's parameters, and those of which it needs at least one: the
// ones that give it a size. Without any of them the effect is zero, which a
// user who named it did not mean.
struct Kind {
  std::vector<std::string> params;
  std::vector<std::string> needs_one_of;
};

const std::map<std::string, Kind>& known() {
  static const std::map<std::string, Kind> k = {
      {"offset", {{"tau0"}, {"tau0"}}},
      {"gravity", {{"A", "phase"}, {"A"}}},
      {"stribeck", {{"excess", "v_s"}, {"excess"}}},
      {"nonlinear_damping", {{"c", "p"}, {"c"}}},
      {"position_friction", {{"depth", "P", "phase"}, {"depth"}}},
      {"periodic_torque", {{"A", "P", "S"}, {"A"}}},
      {"drift", {{"rate", "t0"}, {"rate"}}},
      {"spring", {{"K", "K3", "theta0"}, {"K", "K3"}}},
      {"detent_shape", {{"a2", "b2", "a3", "b3", "a4", "b4"}, {"a2", "b2", "a3", "b3", "a4", "b4"}}},
      {"backlash", {{"width"}, {"width"}}},
      {"hysteresis", {{"presliding"}, {"presliding"}}},
      {"endstop", {{"position", "stiffness", "damping"}, {"position"}}},
      {"compliance", {{"stiffness", "frequency", "damping", "zeta"}, {"stiffness", "frequency"}}},
      {"time_delay", {{"delay"}, {"delay"}}},
      {"saturation", {{"limit"}, {"limit"}}},
  };
  return k;
}

std::string joined(const std::vector<std::string>& names, const char* sep) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : sep) + n;
  return out;
}

std::string known_ids() {
  std::vector<std::string> ids;
  for (const auto& [id, kind] : known()) ids.push_back(id);
  return joined(ids, ", ");
}

double get(const EffectSpec& s, const char* name, double fallback = 0.0) {
  const auto it = s.params.find(name);
  return it == s.params.end() ? fallback : it->second;
}

// A library term as a knob effect: the term by value, evaluated in place.
template <typename F>
class TermEffect final : public KnobEffect {
 public:
  explicit TermEffect(F f) : f_(std::move(f)) {}
  double torque(const KnobMotion& knob, double t) const override { return f_(knob, t); }

 private:
  F f_;
};

template <typename F>
std::unique_ptr<KnobEffect> effect(F f) {
  return std::make_unique<TermEffect<F>>(std::move(f));
}

void require(const EffectSpec& s, bool ok, const char* why) {
  if (!ok) throw std::invalid_argument("effect '" + s.id + "': " + why);
}

// Ranges of the effects that act outside the knob's torque (the torque ones
// take any finite number, as the fitter does).
void check_values(const EffectSpec& s) {
  const auto has = [&](const char* n) { return s.params.count(n) != 0; };
  if (s.id == "hysteresis") {
    require(s, get(s, "presliding") > 0.0 && get(s, "presliding") <= 0.1, "presliding must be in (0, 0.1] rad");
  } else if (s.id == "endstop") {
    require(s, get(s, "position") > 0.0, "position must be > 0 rad (the stops sit at ±position)");
    require(s, get(s, "stiffness") > 0.0, "stiffness must be > 0 N·m/rad");
    require(s, get(s, "damping") >= 0.0, "damping must be >= 0 (dissipative)");
  } else if (s.id == "compliance") {
    require(s, has("stiffness") != has("frequency"), "give exactly one of stiffness and frequency");
    require(s, !(has("damping") && has("zeta")), "give at most one of damping and zeta");
    require(s, get(s, "stiffness", 1.0) > 0.0 && get(s, "frequency", 1.0) > 0.0,
            "stiffness and frequency must be > 0");
    require(s, get(s, "damping") >= 0.0 && get(s, "zeta") >= 0.0, "damping and zeta must be >= 0");
  } else if (s.id == "time_delay") {
    require(s, get(s, "delay") >= 0.0,
            "delay must be >= 0 s (positive: the torque behind the motion; a torque ahead is not modelled)");
    require(s, get(s, "delay") <= 0.1, "delay must be <= 0.1 s");
  } else if (s.id == "saturation") {
    require(s, get(s, "limit") > 0.0, "limit must be > 0 N·m");
  }
}

}  // namespace

std::string EffectSpec::text() const {
  std::string out = id;
  char sep = ':';
  for (const auto& [k, v] : params) {
    char buf[64];
    const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;  // shortest that reads back the same
    out += sep + k + "=" + std::string(buf, end);
    sep = ',';
  }
  return out;
}

namespace {

const Kind& kind_of(const std::string& id) {
  const auto kind = known().find(id);
  if (kind == known().end()) throw std::invalid_argument("unknown effect '" + id + "' (known: " + known_ids() + ")");
  return kind->second;
}

void check_name(const EffectSpec& s, const Kind& kind, const std::string& name) {
  if (std::find(kind.params.begin(), kind.params.end(), name) == kind.params.end())
    throw std::invalid_argument("effect '" + s.id + "' has no parameter '" + name + "' (its parameters: " +
                                joined(kind.params, ", ") + ")");
}

// A whole spec: its values' ranges, and one of the parameters that give it a size.
void check_spec(const EffectSpec& s, const Kind& kind) {
  check_values(s);  // first: its sentences are the more specific ones
  const auto& needs = kind.needs_one_of;
  if (std::none_of(needs.begin(), needs.end(), [&](const std::string& n) { return s.params.count(n) != 0; }))
    throw std::invalid_argument("effect '" + s.id + "' needs " + (needs.size() > 1 ? "one of " : "") +
                                joined(needs, ", ") + ": without " + (needs.size() > 1 ? "any" : "it") +
                                " the effect is zero (its parameters: " + joined(kind.params, ", ") +
                                "; e.g. '" + s.id + ":" + needs.front() + "=…')");
}

}  // namespace

EffectSpec make_effect_spec(const std::string& id, const std::map<std::string, double>& params) {
  const Kind& kind = kind_of(id);
  EffectSpec s{id, params};
  for (const auto& [name, v] : params) {
    check_name(s, kind, name);
    if (!std::isfinite(v)) throw std::invalid_argument("effect '" + id + "': '" + name + "' is not a finite number");
  }
  check_spec(s, kind);
  return s;
}

std::vector<EffectSpec> parse_effect_specs(std::string_view text) {
  std::vector<EffectSpec> out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(';', at), text.size());
    const std::string_view one = text.substr(at, end - at);
    at = end + 1;
    if (one.empty()) continue;
    EffectSpec s;
    const std::size_t colon = one.find(':');
    s.id = std::string(one.substr(0, colon));
    const Kind& kind = kind_of(s.id);
    std::string_view rest = colon == std::string_view::npos ? "" : one.substr(colon + 1);
    while (!rest.empty()) {
      const std::size_t comma = std::min(rest.find(','), rest.size());
      const std::string_view kv = rest.substr(0, comma);
      rest = comma < rest.size() ? rest.substr(comma + 1) : "";
      const std::size_t eq = kv.find('=');
      if (eq == std::string_view::npos)
        throw std::invalid_argument("effect '" + s.id + "': expected name=value, got '" + std::string(kv) + "'");
      const std::string name(kv.substr(0, eq)), value(kv.substr(eq + 1));
      check_name(s, kind, name);
      char* stop = nullptr;
      const double v = std::strtod(value.c_str(), &stop);
      if (value.empty() || *stop != '\0' || !std::isfinite(v))
        throw std::invalid_argument("effect '" + s.id + "': '" + name + "' is not a number: '" + value + "'");
      s.params[name] = v;
    }
    check_spec(s, kind);
    out.push_back(std::move(s));
  }
  return out;
}

bool apply_to_knob(const EffectSpec& s, KnobParams& knob) {
  if (s.id == "spring") {
    knob.spring.K = get(s, "K");
    knob.spring.K3 = get(s, "K3");
    knob.spring.theta0 = get(s, "theta0");
    return true;
  }
  if (s.id == "backlash") {
    knob.backlash = get(s, "width");
    return true;
  }
  if (s.id == "hysteresis") {
    knob.presliding = get(s, "presliding");
    return true;
  }
  if (s.id == "endstop") {
    knob.walls.lo = -get(s, "position");
    knob.walls.hi = get(s, "position");
    knob.walls.K = get(s, "stiffness");
    knob.walls.B = get(s, "damping");
    return true;
  }
  if (s.id == "detent_shape") {
    for (std::size_t k = 2; k <= 4; ++k) {
      knob.detents.a[k] = get(s, ("a" + std::to_string(k)).c_str());
      knob.detents.b[k] = get(s, ("b" + std::to_string(k)).c_str());
    }
    knob.detents.harmonics = std::max<std::size_t>(knob.detents.harmonics, 4);
    return true;
  }
  return false;
}

bool apply_to_plant(const EffectSpec& s, PlantConfig& plant) {
  if (s.id == "time_delay") {
    plant.torque_sensor.delay = get(s, "delay");
    return true;
  }
  if (s.id == "saturation") {
    plant.torque_sensor.saturation = get(s, "limit");
    return true;
  }
  if (s.id != "compliance") return false;
  CouplingParams& c = plant.coupling;
  const double J = plant.knob.inertia.M + c.gripper_inertia;
  const bool tuned = s.params.count("frequency") || s.params.count("zeta");
  require(s, !tuned || J > 0.0, "frequency and zeta need a knob side with inertia (M + gripper > 0)");
  const double k = s.params.count("frequency") ? CouplingParams::tuned(get(s, "frequency"), 1.0, J).stiffness
                                                : get(s, "stiffness");
  if (s.params.count("damping")) {
    c.damping = get(s, "damping");
  } else if (s.params.count("zeta")) {
    c.damping = 2.0 * get(s, "zeta") * std::sqrt(k * J);
  } else {
    c.damping *= std::sqrt(k / c.stiffness);  // the same damping ratio
  }
  c.stiffness = k;
  return true;
}

std::unique_ptr<KnobEffect> make_knob_effect(const EffectSpec& s) {
  if (s.id == "offset") {
    const model::Offset<double> o{get(s, "tau0")};
    return effect([o](const KnobMotion&, double) { return o.torque(); });
  }
  if (s.id == "gravity") {
    const model::OncePerRev<double> g{get(s, "A"), get(s, "phase")};
    return effect([g](const KnobMotion& k, double) { return g.torque(k.theta); });
  }
  if (s.id == "stribeck") {
    const model::Stribeck<double> f{get(s, "excess"), get(s, "v_s", 1.0)};
    return effect([f](const KnobMotion& k, double) { return f.torque(k.omega); });
  }
  if (s.id == "nonlinear_damping") {
    const model::PowerDamping<double> f{get(s, "c"), get(s, "p", 2.0)};
    return effect([f](const KnobMotion& k, double) { return f.torque(k.omega); });
  }
  if (s.id == "position_friction") {
    const model::PositionFriction<double> f{get(s, "depth"), get(s, "P", 1.0), get(s, "phase")};
    return effect([f](const KnobMotion& k, double) { return f.torque(k.theta, k.omega); });
  }
  if (s.id == "periodic_torque") {
    model::Detents<double> w;
    w.A = get(s, "A");
    w.P = get(s, "P", 1.0);
    w.S = get(s, "S");
    return effect([w](const KnobMotion& k, double) { return w.torque(k.theta); });
  }
  if (s.id == "drift") {
    const model::FrictionDrift<double> f{get(s, "rate"), get(s, "t0")};
    return effect([f](const KnobMotion& k, double t) { return f.torque(k.omega, t); });
  }
  throw std::invalid_argument("effect '" + s.id + "' is not a knob torque (fold it into the knob)");
}

}  // namespace knoblab::sim
