// The section named after the study's kind: what a matching, pointing, list
// selection or texture study needs beyond factors and order, checked against
// the factors and stages it refers to.
#include <format>
#include <numbers>

#include "json_reader.hpp"
#include "parse_parts.hpp"

namespace knoblab::study::detail {

namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// The Rendering fields a slider can move, with their Table 9 limits.
struct SliderParameter {
  std::string_view name;
  double limit;
  std::string_view unit;
};
constexpr SliderParameter kSliderParameters[] = {
    {"M_acc", kRenderingLimits.M_acc, "kg·m²"},
    {"B_vel", kRenderingLimits.B_vel, "N·m·s/rad"},
    {"A_pos", kRenderingLimits.A_pos, "N·m"},
    {"detents_per_rev", kRenderingLimits.detents_per_rev, "per revolution"},
};

Slider parse_slider(const nlohmann::json& v, const std::string& path) {
  ObjectReader r(v, path);
  std::vector<std::string_view> names;
  for (const auto& p : kSliderParameters) names.push_back(p.name);
  const std::size_t choice = as_choice(r.require("parameter"), r.path_of("parameter"), names);
  const SliderParameter& parameter = kSliderParameters[choice];
  Slider s;
  s.parameter = std::string(parameter.name);
  s.min = in_range(r.require("min"), r.path_of("min"), 0, parameter.limit, parameter.unit);
  s.max = in_range(r.require("max"), r.path_of("max"), 0, parameter.limit, parameter.unit);
  if (s.max <= s.min) fail(r.path_of("max"), std::format("must be above min ({})", s.min));
  // β of Stevens' power law (slider_mapping.hpp). Stevens' own exponents run
  // from about 0.3 to 3.5; beyond 10 either way a slider would put nearly all
  // of its values at one end.
  if (const nlohmann::json* beta = r.find("perceptual_exponent")) {
    const std::string beta_path = r.path_of("perceptual_exponent");
    s.perceptual_exponent = as_number(*beta, beta_path);
    if (!(s.perceptual_exponent > 0))
      fail(beta_path, std::format("must be above 0 (1 is a linear slider), got {}", s.perceptual_exponent));
    if (s.perceptual_exponent < 0.1 || s.perceptual_exponent > 10)
      fail(beta_path, std::format("must be from 0.1 to 10 (1 is a linear slider), got {}", s.perceptual_exponent));
  }
  r.finish();
  return s;
}

std::vector<std::size_t> all_sliders(const MatchingSettings& m) {
  std::vector<std::size_t> all;
  for (std::size_t i = 0; i < m.sliders.size(); ++i) all.push_back(i);
  return all;
}

// stage_sliders: {stage name: [slider parameter, …]} for every stage, or
// absent for every slider in every stage.
void parse_stage_sliders(const nlohmann::json* v, const std::string& path, const Protocol& protocol,
                         MatchingSettings& m) {
  if (v == nullptr) {
    m.stage_sliders.assign(protocol.stages.size(), all_sliders(m));
    return;
  }
  ObjectReader r(*v, path);
  for (const Stage& stage : protocol.stages) {
    const std::string list_path = r.path_of(stage.name);
    const nlohmann::json& list = r.require(stage.name);
    check_array(list, list_path, 1);
    std::vector<std::size_t> indices;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string item_path = element_path(list_path, i);
      const std::string name = as_string(list[i], item_path);
      std::size_t index = m.sliders.size();
      for (std::size_t s = 0; s < m.sliders.size(); ++s)
        if (m.sliders[s].parameter == name) index = s;
      if (index == m.sliders.size()) fail(item_path, "no slider \"" + name + "\" in sliders");
      for (const std::size_t other : indices)
        if (other == index) fail(item_path, "slider \"" + name + "\" is listed twice");
      indices.push_back(index);
    }
    m.stage_sliders.push_back(std::move(indices));
  }
  r.finish();  // a key that names no stage
}

MatchingSettings parse_matching(const nlohmann::json& v, const std::string& path, const Protocol& protocol) {
  ObjectReader r(v, path);
  MatchingSettings m;
  m.group = as_choice(r.require("group"), r.path_of("group"), {"novice", "expert"}) == 0
                ? MatchingSettings::Group::Novice
                : MatchingSettings::Group::Expert;
  m.think_aloud = r.boolean("think_aloud");
  m.explain_physics = r.boolean("explain_physics");
  const std::string sliders_path = r.path_of("sliders");
  const nlohmann::json& sliders = r.require("sliders");
  check_array(sliders, sliders_path, 1);
  for (std::size_t i = 0; i < sliders.size(); ++i) {
    const std::string slider_path = element_path(sliders_path, i);
    Slider slider = parse_slider(sliders[i], slider_path);
    for (const Slider& other : m.sliders)
      if (other.parameter == slider.parameter)
        fail(member_path(slider_path, "parameter"), "a second slider for " + slider.parameter);
    m.sliders.push_back(std::move(slider));
  }
  parse_stage_sliders(r.find("stage_sliders"), r.path_of("stage_sliders"), protocol, m);
  r.finish();
  return m;
}

PointingSettings parse_pointing(const nlohmann::json& v, const std::string& path, const Protocol& protocol) {
  ObjectReader r(v, path);
  PointingSettings s;
  s.acquisitions = static_cast<unsigned>(as_count(r.require("acquisitions"), r.path_of("acquisitions"), 1, 20));
  s.amplitude_factor = factor_named(protocol, r.require("amplitude_factor"), r.path_of("amplitude_factor"));
  s.width_factor = factor_named(protocol, r.require("width_factor"), r.path_of("width_factor"));
  if (s.width_factor == s.amplitude_factor)
    fail(r.path_of("width_factor"), "must be another factor than amplitude_factor");
  // Each trial's targets come from its levels of these two factors.
  const Factor& amplitudes = protocol.factors[s.amplitude_factor];
  for (std::size_t i = 0; i < amplitudes.levels.size(); ++i)
    if (!amplitudes.levels[i].amplitude_rad)
      fail(std::format("factors[{}].levels[{}].parameters.amplitude_deg", s.amplitude_factor, i),
           "required: the level of pointing.amplitude_factor gives its target's distance");
  const Factor& widths = protocol.factors[s.width_factor];
  for (std::size_t i = 0; i < widths.levels.size(); ++i)
    if (!widths.levels[i].width_rad)
      fail(std::format("factors[{}].levels[{}].parameters.width_deg", s.width_factor, i),
           "required: the level of pointing.width_factor gives its target's width");
  const std::size_t direction = as_choice(r.require("first_direction"), r.path_of("first_direction"),
                                          {"positive", "negative", "alternate", "random"});
  s.first_direction = static_cast<Direction>(direction);
  s.home_width_rad = in_range(r.require("home_width_deg"), r.path_of("home_width_deg"), 0, 90, "°") * kRadPerDeg;
  if (s.home_width_rad <= 0) fail(r.path_of("home_width_deg"), "must be above 0");
  r.finish();
  return s;
}

ListSelectionSettings parse_list_selection(const nlohmann::json& v, const std::string& path, const Protocol& protocol) {
  ObjectReader r(v, path);
  ListSelectionSettings s;
  s.list_length = static_cast<unsigned>(as_count(r.require("list_length"), r.path_of("list_length"), 2, 10'000));
  s.items_per_rev = in_range(r.require("items_per_rev"), r.path_of("items_per_rev"), 0, 360, "per revolution");
  if (s.items_per_rev <= 0) fail(r.path_of("items_per_rev"), "must be above 0");
  s.context_factor = factor_named(protocol, r.require("context_factor"), r.path_of("context_factor"));
  const Factor& context = protocol.factors[s.context_factor];
  const std::string freeform = r.string("freeform_level");
  const auto level = context.level_index(freeform);
  if (!level) fail(r.path_of("freeform_level"), "factor " + context.name + " has no level \"" + freeform + "\"");
  s.freeform_level = *level;
  s.exploration_s = in_range(r.require("exploration_s"), r.path_of("exploration_s"), 0, 600, "s");
  if (s.exploration_s <= 0) fail(r.path_of("exploration_s"), "must be above 0");
  s.rating_s = in_range(r.require("rating_s"), r.path_of("rating_s"), 0, 600, "s");
  s.rest_s = in_range(r.require("rest_s"), r.path_of("rest_s"), 0, 600, "s");
  r.finish();
  return s;
}

TexturesSettings parse_textures(const nlohmann::json& v, const std::string& path, const Protocol& protocol) {
  ObjectReader r(v, path);
  TexturesSettings s;
  s.factor = factor_named(protocol, r.require("factor"), r.path_of("factor"));
  s.stroke_min_s = in_range(r.require("stroke_min_s"), r.path_of("stroke_min_s"), 0, 60, "s");
  if (s.stroke_min_s <= 0) fail(r.path_of("stroke_min_s"), "must be above 0");
  s.stroke_max_s = in_range(r.require("stroke_max_s"), r.path_of("stroke_max_s"), 0, 60, "s");
  if (s.stroke_max_s < s.stroke_min_s)
    fail(r.path_of("stroke_max_s"), std::format("must be at least stroke_min_s ({})", s.stroke_min_s));
  s.blindfold = r.boolean("blindfold");
  r.finish();
  return s;
}

}  // namespace

KindSettings parse_kind_settings(const nlohmann::json& v, const std::string& path, const Protocol& protocol) {
  switch (protocol.kind) {
    case Kind::Matching: return parse_matching(v, path, protocol);
    case Kind::Pointing: return parse_pointing(v, path, protocol);
    case Kind::ListSelection: return parse_list_selection(v, path, protocol);
    case Kind::Textures: return parse_textures(v, path, protocol);
  }
  fail(path, "unknown kind");
}

}  // namespace knoblab::study::detail
