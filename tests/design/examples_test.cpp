// examples/designs/fan-knob.json is the fan knob built from the templates
// (fan_knob_steps.hpp), so the example cannot drift from the steps the docs
// and the UI test walk through. KNOBLAB_UPDATE_EXAMPLES=1 rewrites it.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "fan_knob_steps.hpp"
#include "knoblab/design/design_json.hpp"

namespace knoblab::design {
namespace {

TEST(Examples, TheShippedFanKnobIsTheOneTheTemplatesMake) {
  const std::filesystem::path file = std::filesystem::path(KNOBLAB_DESIGN_EXAMPLES_DIR) / "fan-knob.json";
  const Design built = testing::fan_knob();
  if (const char* update = std::getenv("KNOBLAB_UPDATE_EXAMPLES"); update && std::string(update) == "1")
    write_design(file, built);
  EXPECT_EQ(read_design(file), built) << "rerun with KNOBLAB_UPDATE_EXAMPLES=1 if the steps changed on purpose";
}

}  // namespace
}  // namespace knoblab::design
