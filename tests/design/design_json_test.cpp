// Design files: saved and read back identically; every malformed file is
// refused with a sentence naming the key; a failed save leaves the old file.
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fan_knob_steps.hpp"
#include "knoblab/design/design_json.hpp"

namespace knoblab::design {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("knoblab-design-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::string error_of(const json& j) {
  try {
    design_from_json(j);
  } catch (const jsonread::PathError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(DesignJson, TheFanKnobIsSavedAndReadBackIdentically) {
  const Design d = testing::fan_knob();
  const auto file = scratch("fan.json");
  write_design(file, d);
  EXPECT_EQ(read_design(file), d);
  EXPECT_FALSE(std::filesystem::exists(file.string() + ".tmp"));
}

TEST(DesignJson, TheFileKeepsWaveformsAsColumnsOtherToolsRead) {
  const json j = to_json(testing::fan_knob());
  EXPECT_EQ(j["format"], "knoblab-design");
  const json& w = j["channels"]["position"]["lines"][0]["tiles"][1]["tile"]["waveform"];
  EXPECT_TRUE(w["x"].is_array());
  EXPECT_EQ(w["x"].size(), w["y"].size());
}

TEST(DesignJson, MalformedFilesAreRefusedWithTheKeyAndWhatIsWrong) {
  const json good = to_json(testing::fan_knob());
  json j = good;
  j["channels"]["position"]["lines"][0]["tiles"][1]["to"] = -2.0;
  EXPECT_THAT(error_of(j), HasSubstr("channels.position.lines[0].tiles[1].to: must be more than from"));
  j = good;
  j["channels"]["velocity"]["lines"][0]["tiles"][0]["tile"]["waveform"]["y"].erase(0);
  EXPECT_EQ(error_of(j), "channels.velocity.lines[0].tiles[0].tile.waveform.y: has 2 values but x has 3; give one y per x");
  j = good;
  j["palette"][0]["tiles"][1]["waveform"]["x"][2] = 0.0;
  EXPECT_EQ(error_of(j),
            "palette[0].tiles[1].waveform: the waveform must have its points left to right, each x after the last");
  j = good;
  j["channels"]["pressure"] = json::object();
  EXPECT_THAT(error_of(j), HasSubstr("channels.pressure: unknown key"));
  j = good;
  j["palette"][0]["tiles"][0]["drawn_for"] = "jerk";
  EXPECT_EQ(error_of(j), "palette[0].tiles[0].drawn_for: unknown value \"jerk\" (use position, velocity, acceleration, time)");
  j = good;
  j["version"] = 2;
  EXPECT_EQ(error_of(j), "version: this knoblab reads version 1, got 2");
  EXPECT_EQ(error_of(json::array()), "design: expected an object, got []");
}

TEST(DesignJson, AFileThatIsNotJsonNamesTheFile) {
  const auto file = scratch("broken.json");
  std::ofstream(file) << "{\"format\": \"knoblab-design\", ";
  try {
    read_design(file);
    FAIL() << "accepted";
  } catch (const jsonread::PathError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string() + ": not JSON"));
  }
}

TEST(DesignJson, ADesignNestedBeyondSixtyFourLevelsIsRefusedNamingTheFile) {
  const auto file = scratch("deep.json");
  std::ofstream(file) << "{\"palette\": " << std::string(1000000, '[') << std::string(1000000, ']') << "}";
  try {
    read_design(file);
    FAIL() << "accepted";
  } catch (const jsonread::PathError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string() + ": not JSON we read: nested deeper than 64 levels at byte 76"));
  }
}

TEST(DesignJson, ASaveThatCannotBeWrittenLeavesTheOldFileWhole) {
  const auto dir = scratch("ro");
  std::filesystem::create_directories(dir);
  const auto file = dir / "d.json";
  write_design(file, testing::fan_knob());
  const std::string before = [&] { std::ifstream in(file); return std::string(std::istreambuf_iterator<char>(in), {}); }();
  std::filesystem::create_directory(file.string() + ".tmp");  // the temporary cannot be created
  EXPECT_THROW(write_design(file, Design{}), std::runtime_error);
  std::ifstream in(file);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), before);
  std::filesystem::remove(file.string() + ".tmp");
}

}  // namespace
}  // namespace knoblab::design
