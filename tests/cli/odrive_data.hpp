// The real ODrive recordings (../shared/datasets/odrive-cogging) for the
// cli tests: where they are and how `knoblab convert` reads them.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace knoblab::test {

// $KNOBLAB_SHARED (./run sets it), else ../shared beside the repo.
inline std::filesystem::path odrive_dir() {
  const char* env = std::getenv("KNOBLAB_SHARED");
  const std::filesystem::path shared = env && *env ? env : KNOBLAB_SHARED_DIR;
  return shared / "datasets" / "odrive-cogging";
}

// Skipped on a checkout without ../shared; CI has it, so there it fails.
#define REQUIRE_DATASET()                                                              \
  do {                                                                                 \
    if (!std::filesystem::is_directory(::knoblab::test::odrive_dir())) {               \
      const char* ci = std::getenv("CI");                                              \
      if (ci && std::string(ci) == "true") FAIL() << "CI: no dataset at " << ::knoblab::test::odrive_dir(); \
      GTEST_SKIP() << "no dataset at " << ::knoblab::test::odrive_dir();               \
    }                                                                                  \
  } while (0)

// 8192 counts per revolution, 0.0551 N·m/A (the dataset's README).
inline std::vector<std::string> odrive_args(const std::filesystem::path& in,
                                            const std::filesystem::path& out) {
  return {"convert", in.string(), out.string(), "--columns", "t,theta,torque", "--counts-per-rev", "8192",
          "--torque-scale", "0.0551", "--unwrap", "--knob", "odrive-gimbal"};
}

}  // namespace knoblab::test
