// The example protocols cut short for tests: the same studies, fewer trials.
#pragma once

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "knoblab/study/protocol.hpp"

namespace knoblab::test {

inline nlohmann::json example_protocol(const std::string& name) {
  std::ifstream in(std::string(KNOBLAB_STUDY_EXAMPLES_DIR) + "/" + name + ".json");
  return nlohmann::json::parse(in);
}

// Keeps only the named levels of a factor.
inline void keep_levels(nlohmann::json& p, const std::string& factor, const std::vector<std::string>& keep) {
  for (auto& f : p["factors"]) {
    if (f["name"] != factor) continue;
    nlohmann::json levels = nlohmann::json::array();
    for (const auto& l : f["levels"])
      if (std::find(keep.begin(), keep.end(), l["name"].get<std::string>()) != keep.end()) levels.push_back(l);
    f["levels"] = levels;
  }
}

// Rotary pointing: two renderings, one amplitude, both widths; one block, no practice.
inline nlohmann::json shortened_pointing_json() {
  nlohmann::json p = example_protocol("pointing");
  p["study"] = "pointing-short";
  p["blocks"] = 1;
  p["practice"] = nlohmann::json::object();
  keep_levels(p, "knob", {"not-rendered", "high-inertia"});
  keep_levels(p, "amplitude", {"A30"});
  return p;
}

// Matching (novices): one knob in each stage, once each.
inline nlohmann::json shortened_matching_json() {
  nlohmann::json p = example_protocol("matching-novice");
  p["study"] = "matching-short";
  p["repetitions"] = 1;
  keep_levels(p, "knob", {"A", "C"});
  p["stages"][0]["levels"]["knob"] = {"A"};
  p["stages"][1]["levels"]["knob"] = {"C"};
  return p;
}

// List selection: two stimuli in each context, once, short exploration, no practice.
inline nlohmann::json shortened_list_json() {
  nlohmann::json p = example_protocol("list-selection");
  p["study"] = "list-short";
  p["repetitions"] = 1;
  p["practice"] = nlohmann::json::object();
  p["list_selection"]["exploration_s"] = 1.5;
  keep_levels(p, "knob", {"not-rendered", "few-detents"});
  return p;
}

inline study::Protocol shortened_pointing() { return study::parse_protocol(shortened_pointing_json()); }
inline study::Protocol shortened_matching() { return study::parse_protocol(shortened_matching_json()); }
inline study::Protocol shortened_list() { return study::parse_protocol(shortened_list_json()); }

}  // namespace knoblab::test
