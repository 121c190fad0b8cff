#include "model_input.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "commands.hpp"
#include "knoblab/discovery/model_file.hpp"

namespace knoblab::cli {

ModelInput read_model_input(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError("--model: cannot read '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  ModelInput out;
  out.text = s.str();
  try {
    out.knob = discovery::parse_model_file(out.text, path);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return out;
}

}  // namespace knoblab::cli
