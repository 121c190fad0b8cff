// The protocol file's top level: identity, stages, blocking, practice, order,
// seed, ratings and biometrics. Factors and kind settings have their own files.
#include "knoblab/study/protocol.hpp"

#include <fstream>
#include <sstream>

#include "json_reader.hpp"
#include "knoblab/jsonread/nesting.hpp"
#include "parse_parts.hpp"

namespace knoblab::study {

using detail::ObjectReader;
using detail::element_path;
using detail::fail;
using detail::member_path;

namespace {

constexpr Kind kKinds[] = {Kind::Matching, Kind::Pointing, Kind::ListSelection, Kind::Textures};
constexpr Scale kScales[] = {Scale::SamValence, Scale::SamArousal, Scale::AffectGrid, Scale::Satisfaction,
                             Scale::Appropriateness};

std::vector<std::string_view> kind_names() {
  std::vector<std::string_view> names;
  for (const Kind k : kKinds) names.push_back(kind_name(k));
  return names;
}

// The conditions of a stage: the product of its allowed level sets.
std::size_t stage_size(const Stage& stage) {
  std::size_t n = 1;
  for (const auto& allowed : stage.allowed) n *= allowed.size();
  return n;
}

bool stages_overlap(const Stage& a, const Stage& b) {
  for (std::size_t f = 0; f < a.allowed.size(); ++f) {
    bool shared = false;
    for (const std::size_t level : a.allowed[f])
      for (const std::size_t other : b.allowed[f]) shared = shared || level == other;
    if (!shared) return false;
  }
  return true;
}

Stage parse_stage(const nlohmann::json& v, const std::string& path, const std::vector<Factor>& factors) {
  ObjectReader r(v, path);
  Stage stage;
  stage.name = r.string("name");
  detail::check_name(stage.name, r.path_of("name"));
  ObjectReader levels(r.require("levels"), r.path_of("levels"));
  for (const Factor& factor : factors) {
    std::vector<std::size_t> allowed;
    const nlohmann::json* names = levels.find(factor.name);
    if (names == nullptr) {
      for (std::size_t i = 0; i < factor.levels.size(); ++i) allowed.push_back(i);
    } else {
      const std::string list_path = levels.path_of(factor.name);
      detail::check_array(*names, list_path, 1);
      std::vector<bool> taken(factor.levels.size(), false);
      for (std::size_t i = 0; i < names->size(); ++i) {
        const std::string item_path = element_path(list_path, i);
        const std::string name = detail::as_string((*names)[i], item_path);
        const auto index = factor.level_index(name);
        if (!index) fail(item_path, "factor " + factor.name + " has no level \"" + name + "\"");
        if (taken[*index]) fail(item_path, "level \"" + name + "\" is listed twice");
        taken[*index] = true;
      }
      // The factor's own order, whatever the list's: the plan's "listed order".
      for (std::size_t i = 0; i < taken.size(); ++i)
        if (taken[i]) allowed.push_back(i);
    }
    stage.allowed.push_back(std::move(allowed));
  }
  levels.finish();  // a key that is no factor's name
  r.finish();
  return stage;
}

// Stages must split the conditions: each in exactly one stage, so that the
// plan runs every condition the planned number of times.
std::vector<Stage> parse_stages(const nlohmann::json* v, const std::vector<Factor>& factors) {
  std::vector<Stage> stages;
  std::size_t conditions = 1;
  for (const Factor& factor : factors) conditions *= factor.levels.size();
  if (v == nullptr) {
    Stage all{"all", {}};
    for (const Factor& factor : factors) {
      all.allowed.emplace_back();
      for (std::size_t i = 0; i < factor.levels.size(); ++i) all.allowed.back().push_back(i);
    }
    stages.push_back(std::move(all));
    return stages;
  }
  const nlohmann::json& array = *v;
  detail::check_array(array, "stages", 1);
  std::size_t covered = 0;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const std::string path = element_path("stages", i);
    Stage stage = parse_stage(array[i], path, factors);
    for (std::size_t j = 0; j < stages.size(); ++j) {
      if (stages[j].name == stage.name) fail(member_path(path, "name"), "stage \"" + stage.name + "\" is named twice");
      if (stages_overlap(stages[j], stage))
        fail(path, "shares conditions with " + element_path("stages", j) + " (each condition belongs to one stage)");
    }
    covered += stage_size(stage);
    stages.push_back(std::move(stage));
  }
  if (covered != conditions)
    fail("stages", "take " + std::to_string(covered) + " of the " + std::to_string(conditions) +
                       " conditions; every condition must belong to a stage");
  return stages;
}

Practice parse_practice(const nlohmann::json& v, std::size_t blocks) {
  ObjectReader r(v, "practice");
  Practice p;
  if (const nlohmann::json* b = r.find("blocks")) {
    p.blocks = detail::as_count(*b, r.path_of("blocks"), 0, 100);
    if (p.blocks >= blocks)
      fail(r.path_of("blocks"), "must be fewer than blocks (" + std::to_string(blocks) + "), or nothing is analysed");
  }
  if (const nlohmann::json* t = r.find("trials")) p.trials = detail::as_count(*t, r.path_of("trials"), 0, 1000);
  if (p.blocks > 0 && p.trials > 0)
    fail("practice", "give blocks or trials, not both (practice trials open each stage of the first block)");
  r.finish();
  return p;
}

Order parse_order(const nlohmann::json& v, const Protocol& protocol) {
  ObjectReader r(v, "order");
  Order order;
  const std::size_t scheme =
      detail::as_choice(r.require("scheme"), r.path_of("scheme"), {"random", "latin_square", "fixed"});
  order.scheme = scheme == 0 ? OrderScheme::Random : scheme == 1 ? OrderScheme::LatinSquare : OrderScheme::Fixed;
  if (order.scheme == OrderScheme::LatinSquare) {
    order.factor = detail::factor_named(protocol, r.require("factor"), r.path_of("factor"));
  } else if (r.find("factor") != nullptr) {
    fail(r.path_of("factor"), "only a latin_square order is over a factor");
  }
  r.finish();
  return order;
}

Rating parse_rating(const nlohmann::json& v, const std::string& path) {
  ObjectReader r(v, path);
  Rating rating;
  std::vector<std::string_view> names;
  for (const Scale s : kScales) names.push_back(scale_name(s));
  rating.scale = kScales[detail::as_choice(r.require("scale"), r.path_of("scale"), names)];
  rating.min = static_cast<int>(detail::as_count(r.require("min"), r.path_of("min"), 0, 99));
  rating.max = static_cast<int>(detail::as_count(r.require("max"), r.path_of("max"), 1, 100));
  if (rating.max <= rating.min)
    fail(r.path_of("max"), "must be above min (" + std::to_string(rating.min) + ")");
  // Required: the thesis used both directions, so no default is safe.
  rating.min_is = detail::as_choice(r.require("min_is"), r.path_of("min_is"), {"low", "high"}) == 0 ? ScaleEnd::Low
                                                                                                     : ScaleEnd::High;
  rating.prompt = r.string_or("prompt", "");
  r.finish();
  return rating;
}

std::vector<Rating> parse_ratings(const nlohmann::json& v) {
  const nlohmann::json& array = v;
  detail::check_array(array, "ratings", 1);
  std::vector<Rating> ratings;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const std::string path = element_path("ratings", i);
    Rating rating = parse_rating(array[i], path);
    for (const Rating& other : ratings)
      if (other.scale == rating.scale)
        fail(member_path(path, "scale"), std::string(scale_name(rating.scale)) + " is asked twice");
    ratings.push_back(std::move(rating));
  }
  return ratings;
}

Biometrics parse_biometrics(const nlohmann::json& v) {
  ObjectReader r(v, "biometrics");
  Biometrics b;
  b.emg = r.boolean("emg");
  b.sc = r.boolean("sc");
  r.finish();
  return b;
}

}  // namespace

std::string_view kind_name(Kind kind) {
  switch (kind) {
    case Kind::Matching: return "matching";
    case Kind::Pointing: return "pointing";
    case Kind::ListSelection: return "list_selection";
    case Kind::Textures: return "textures";
  }
  return "?";
}

std::string_view scale_name(Scale scale) {
  switch (scale) {
    case Scale::SamValence: return "sam_valence";
    case Scale::SamArousal: return "sam_arousal";
    case Scale::AffectGrid: return "affect_grid";
    case Scale::Satisfaction: return "satisfaction";
    case Scale::Appropriateness: return "appropriateness";
  }
  return "?";
}

std::optional<std::size_t> Factor::level_index(std::string_view level) const {
  for (std::size_t i = 0; i < levels.size(); ++i)
    if (levels[i].name == level) return i;
  return std::nullopt;
}

std::optional<std::size_t> Protocol::factor_index(std::string_view name) const {
  for (std::size_t i = 0; i < factors.size(); ++i)
    if (factors[i].name == name) return i;
  return std::nullopt;
}

Protocol parse_protocol(const nlohmann::json& file) {
  ObjectReader r(file, "", "protocol");
  Protocol p;
  p.study = r.string("study");
  detail::check_name(p.study, "study");
  p.kind = kKinds[detail::as_choice(r.require("kind"), "kind", kind_names())];
  p.title = r.string("title");
  p.source = r.string_or("source", "");
  if (const nlohmann::json* notes = r.find("notes")) {
    detail::check_array(*notes, "notes", 0);
    for (std::size_t i = 0; i < notes->size(); ++i)
      p.notes.push_back(detail::as_string((*notes)[i], element_path("notes", i)));
  }
  p.factors = detail::parse_factors(r.require("factors"), "factors");
  p.stages = parse_stages(r.find("stages"), p.factors);
  p.blocks = detail::as_count(r.require("blocks"), "blocks", 1, 100);
  p.repetitions = detail::as_count(r.require("repetitions"), "repetitions", 1, 100);
  p.practice = parse_practice(r.require("practice"), p.blocks);
  p.order = parse_order(r.require("order"), p);
  p.seed = detail::as_uint64(r.require("seed"), "seed");
  p.ratings = parse_ratings(r.require("ratings"));
  p.biometrics = parse_biometrics(r.require("biometrics"));
  for (const Kind other : kKinds) {
    const std::string_view name = kind_name(other);
    if (other != p.kind && r.find(name) != nullptr)
      fail(std::string(name), "settings for kind " + std::string(name) + ", but this study's kind is " +
                                  std::string(kind_name(p.kind)));
  }
  const std::string section(kind_name(p.kind));
  p.settings = detail::parse_kind_settings(r.require(section), section, p);
  r.finish();
  return p;
}

Protocol parse_protocol_text(std::string_view text) {
  if (const auto deep = jsonread::nesting_problem(text)) throw ProtocolError("", "not JSON we read: " + *deep);
  nlohmann::json file;
  try {
    file = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw ProtocolError("", std::string("not JSON: ") + e.what());
  }
  return parse_protocol(file);
}

Protocol load_protocol(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw ProtocolError("", "cannot read " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return parse_protocol_text(text.str());
  } catch (const ProtocolError& e) {
    throw e.in_file(path.string());
  }
}

}  // namespace knoblab::study
