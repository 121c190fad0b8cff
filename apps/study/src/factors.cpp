// factors: [{name, levels: [{name, description?, preset?, parameters?}]}]
#include <format>
#include <numbers>

#include "json_reader.hpp"
#include "knoblab/sim/presets.hpp"
#include "parse_parts.hpp"

namespace knoblab::study::detail {

namespace {

// Enough for any factorial design a participant can sit through; a bound
// keeps a typo (a huge level list) from building an enormous plan.
constexpr std::size_t kMaxConditions = 10'000;

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// One rendering term: absent is zero, present is SI within Table 9's limit.
// The hint names the SI form because the thesis tables print mN·m.
double term(ObjectReader& r, std::string_view key, double limit, std::string_view unit, bool& any) {
  const nlohmann::json* v = r.find(key);
  if (v == nullptr) return 0.0;
  any = true;
  const std::string path = r.path_of(key);
  const double x = as_number(*v, path);
  if (x < 0) fail(path, std::format("must not be negative, got {}", x));
  if (x > limit)
    fail(path, std::format("must be at most {} {} (the haptic knob's continuous limit, thesis Table 9; values are SI, "
                           "so 2.6 mN·m is 0.0026), got {}",
                           limit, unit, x));
  return x;
}

void parse_parameters(const nlohmann::json& v, const std::string& path, Level& level) {
  ObjectReader r(v, path);
  bool any = false;
  Rendering g;
  g.M_acc = term(r, "M_acc", kRenderingLimits.M_acc, "kg·m²", any);
  g.B_vel = term(r, "B_vel", kRenderingLimits.B_vel, "N·m·s/rad", any);
  g.A_pos = term(r, "A_pos", kRenderingLimits.A_pos, "N·m", any);
  g.detents_per_rev = term(r, "detents_per_rev", kRenderingLimits.detents_per_rev, "per revolution", any);
  if (g.A_pos > 0 && g.detents_per_rev <= 0)
    fail(r.path_of("detents_per_rev"), "must be above 0 when A_pos is (detents need a period)");
  if (any) level.rendering = g;
  if (const nlohmann::json* a = r.find("amplitude_deg"))
    level.amplitude_rad = in_range(*a, r.path_of("amplitude_deg"), 0, 720, "°") * kRadPerDeg;
  if (const nlohmann::json* w = r.find("width_deg"))
    level.width_rad = in_range(*w, r.path_of("width_deg"), 0, 90, "°") * kRadPerDeg;
  if (level.amplitude_rad == 0.0) fail(r.path_of("amplitude_deg"), "must be above 0");
  if (level.width_rad == 0.0) fail(r.path_of("width_deg"), "must be above 0");
  r.finish();
}

Level parse_level(const nlohmann::json& v, const std::string& path) {
  ObjectReader r(v, path);
  Level level;
  level.name = r.string("name");
  check_name(level.name, r.path_of("name"));
  level.description = r.string_or("description", "");
  level.preset = r.string_or("preset", "");
  if (!level.preset.empty() && sim::presets::find(level.preset) == nullptr)
    fail(r.path_of("preset"), "no simulator preset \"" + level.preset + "\" (see knoblab simulate --list)");
  if (const nlohmann::json* p = r.find("parameters")) parse_parameters(*p, r.path_of("parameters"), level);
  r.finish();
  return level;
}

Factor parse_factor(const nlohmann::json& v, const std::string& path) {
  ObjectReader r(v, path);
  Factor factor;
  factor.name = r.string("name");
  check_name(factor.name, r.path_of("name"));
  const std::string levels_path = r.path_of("levels");
  const nlohmann::json& levels = r.require("levels");
  check_array(levels, levels_path, 1);
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const std::string level_path = element_path(levels_path, i);
    Level level = parse_level(levels[i], level_path);
    if (factor.level_index(level.name))
      fail(member_path(level_path, "name"), "level \"" + level.name + "\" is already in factor " + factor.name);
    factor.levels.push_back(std::move(level));
  }
  r.finish();
  return factor;
}

}  // namespace

void check_name(const std::string& name, const std::string& path) {
  if (name.size() > 64) fail(path, "must be at most 64 characters");
  for (const char c : name) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
                    c == '_' || c == '.';
    if (!ok) fail(path, "\"" + name + "\": use only letters, digits, '-', '_' and '.'");
  }
}

double in_range(const nlohmann::json& v, const std::string& path, double min, double max, std::string_view unit) {
  const double x = as_number(v, path);
  if (x < min || x > max) fail(path, std::format("must be from {} to {} {}, got {}", min, max, unit, x));
  return x;
}

std::vector<Factor> parse_factors(const nlohmann::json& v, const std::string& path) {
  const nlohmann::json& array = v;
  check_array(array, path, 1);
  std::vector<Factor> factors;
  std::size_t conditions = 1;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const std::string factor_path = element_path(path, i);
    Factor factor = parse_factor(array[i], factor_path);
    for (const Factor& other : factors)
      if (other.name == factor.name)
        fail(member_path(factor_path, "name"), "factor \"" + factor.name + "\" is named twice");
    conditions *= factor.levels.size();
    if (conditions > kMaxConditions)
      fail(path, std::format("more than {} conditions (levels multiplied over factors)", kMaxConditions));
    factors.push_back(std::move(factor));
  }
  return factors;
}

std::size_t factor_named(const Protocol& protocol, const nlohmann::json& v, const std::string& path) {
  const std::string name = as_string(v, path);
  if (const auto f = protocol.factor_index(name)) return *f;
  std::string list;
  for (const Factor& factor : protocol.factors) list += (list.empty() ? "" : ", ") + factor.name;
  fail(path, "no factor named \"" + name + "\" (factors: " + list + ")");
}

}  // namespace knoblab::study::detail
