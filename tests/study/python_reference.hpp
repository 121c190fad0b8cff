// shuffle_reference.py, the independent Python re-implementation of the
// plan's randomness, run at test time. A missing python3 fails the test
// that needs it; it is never a skip.
#pragma once

#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace knoblab::study::test {

inline std::string run_python_reference(const std::string& args) {
  const std::string python = KNOBLAB_STUDY_PYTHON3;
  if (python.empty() || python.ends_with("-NOTFOUND"))
    throw std::runtime_error("python3 was not found when the tests were configured; the cross-check cannot run");
  const std::string command = python + " '" + KNOBLAB_STUDY_REFERENCE + "' " + args;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot run " + command);
  std::string output;
  std::array<char, 4096> buffer{};
  while (const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), got);
  if (pclose(pipe) != 0) throw std::runtime_error(command + " failed:\n" + output);
  return output;
}

}  // namespace knoblab::study::test
