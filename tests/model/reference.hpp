// Reader for the scipy reference files in tests/reference (model_*.txt):
// '#' comments, then blocks "@ name count" followed by count numbers.
#pragma once

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace knoblab::model::test {

class Reference {
 public:
  explicit Reference(const std::string& file) {
    const std::string path = std::string(KNOBLAB_MODEL_REFERENCE_DIR) + "/" + file;
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      if (line[0] != '@') throw std::runtime_error(path + ": expected '@ name count'");
      std::istringstream header(line.substr(1));
      std::string name;
      std::size_t count = 0;
      header >> name >> count;
      std::vector<double>& values = blocks_[name];
      values.reserve(count);
      for (std::size_t i = 0; i < count && std::getline(in, line); ++i)
        values.push_back(std::stod(line));
      if (values.size() != count) throw std::runtime_error(path + ": short block " + name);
    }
  }
  const std::vector<double>& operator[](const std::string& name) const {
    const auto it = blocks_.find(name);
    if (it == blocks_.end()) throw std::runtime_error("no reference block " + name);
    return it->second;
  }

 private:
  std::map<std::string, std::vector<double>> blocks_;
};

// Largest |a − b| over the vectors, divided by the largest |b| (signal scale).
inline double relative_max_error(const std::vector<double>& a, const std::vector<double>& b) {
  double err = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    err = std::max(err, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return a.size() == b.size() ? err / scale : 1e300;
}

}  // namespace knoblab::model::test
