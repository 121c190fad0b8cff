// The protocol files in examples/studies, for the tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/study/protocol.hpp"

namespace knoblab::study::test {

inline std::filesystem::path example_path(const std::string& name) {
  return std::filesystem::path(KNOBLAB_STUDY_EXAMPLES_DIR) / name;
}

inline nlohmann::json example_json(const std::string& name) {
  std::ifstream in(example_path(name));
  return nlohmann::json::parse(in);
}

inline Protocol example(const std::string& name) { return load_protocol(example_path(name)); }

inline const std::vector<std::string>& example_names() {
  static const std::vector<std::string> names = {"pointing.json", "matching-novice.json", "matching-expert.json",
                                                 "list-selection.json", "textures.json"};
  return names;
}

}  // namespace knoblab::study::test
