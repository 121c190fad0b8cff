// A malformed protocol is refused with a ProtocolError whose path names the
// offending key, so the person editing the file knows where to look.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "examples.hpp"

namespace knoblab::study {
namespace {

using nlohmann::json;
using test::example_json;

struct Refusal {
  std::string path;
  std::string message;
};

// The error parsing `file` gives; a failure if it parses.
Refusal refusal(const json& file) {
  try {
    parse_protocol(file);
  } catch (const ProtocolError& e) {
    EXPECT_EQ(std::string(e.what()), e.path().empty() ? e.message() : e.path() + ": " + e.message());
    return {e.path(), e.message()};
  }
  ADD_FAILURE() << "the protocol was accepted";
  return {};
}

// Edits example `name` at a JSON pointer (or removes the key) and expects a
// refusal at `path` whose message contains `words`.
void expect_refused(const std::string& name, const std::string& pointer, const json& value, const std::string& path,
                    const std::string& words) {
  json file = example_json(name);
  if (value.is_discarded()) {
    const json::json_pointer p(pointer);
    file[p.parent_pointer()].erase(p.back());
  } else {
    file[json::json_pointer(pointer)] = value;
  }
  const Refusal r = refusal(file);
  EXPECT_EQ(r.path, path) << r.message;
  EXPECT_NE(r.message.find(words), std::string::npos) << "message: " << r.message;
}

const json kRemove = json(json::value_t::discarded);

TEST(ProtocolErrors, AProtocolNestedBeyondSixtyFourLevelsIsRefusedBeforeItIsParsed) {
  const std::string deep = "{\"study\": " + std::string(1000000, '[') + std::string(1000000, ']') + "}";
  try {
    parse_protocol_text(deep);
    FAIL() << "accepted";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.message(), "not JSON we read: nested deeper than 64 levels at byte 74");
  }
}

TEST(ProtocolErrors, ARenderingAboveTheKnobsLimitNamesTheParameterAndSaysSi) {
  // 2.6 is Table 19's damping in mN·m/(rad/s), written without converting.
  expect_refused("list-selection.json", "/factors/1/levels/0/parameters/B_vel", 2.6,
                 "factors[1].levels[0].parameters.B_vel", "at most 0.045");
  expect_refused("list-selection.json", "/factors/1/levels/0/parameters/B_vel", 2.6,
                 "factors[1].levels[0].parameters.B_vel", "SI");
}

TEST(ProtocolErrors, NegativeAndNonNumericParametersAreRefused) {
  expect_refused("pointing.json", "/factors/0/levels/3/parameters/M_acc", -1e-5,
                 "factors[0].levels[3].parameters.M_acc", "negative");
  expect_refused("pointing.json", "/factors/0/levels/3/parameters/M_acc", "0.06",
                 "factors[0].levels[3].parameters.M_acc", "expected a number");
}

TEST(ProtocolErrors, DetentsWithoutAPeriodAreRefused) {
  expect_refused("pointing.json", "/factors/0/levels/5/parameters/detents_per_rev", 0,
                 "factors[0].levels[5].parameters.detents_per_rev", "above 0");
}

TEST(ProtocolErrors, UnknownKeysAreRefusedAtEveryDepth) {
  expect_refused("pointing.json", "/seeds", 1, "seeds", "unknown key");
  expect_refused("pointing.json", "/factors/0/levels/1/parameters/B_visc", 0.001,
                 "factors[0].levels[1].parameters.B_visc", "unknown key");
  expect_refused("pointing.json", "/factors/0/levels/1/colour", "red", "factors[0].levels[1].colour", "unknown key");
  expect_refused("pointing.json", "/pointing/acquisition", 3, "pointing.acquisition", "unknown key");
  expect_refused("pointing.json", "/ratings/0/direction", "up", "ratings[0].direction", "unknown key");
  expect_refused("pointing.json", "/biometrics/ecg", true, "biometrics.ecg", "unknown key");
}

TEST(ProtocolErrors, AnUnknownKeyListsTheKnownOnes) {
  json file = example_json("pointing.json");
  file["practice"]["block"] = 1;
  EXPECT_NE(refusal(file).message.find("blocks"), std::string::npos);
}

TEST(ProtocolErrors, MissingRequiredKeysAreNamed) {
  expect_refused("pointing.json", "/seed", kRemove, "seed", "required key is missing");
  expect_refused("pointing.json", "/ratings/0/min_is", kRemove, "ratings[0].min_is", "required key is missing");
  expect_refused("pointing.json", "/factors/2/levels/0/name", kRemove, "factors[2].levels[0].name",
                 "required key is missing");
  expect_refused("pointing.json", "/pointing", kRemove, "pointing", "required key is missing");
}

TEST(ProtocolErrors, WrongTypesAndOutOfRangeCountsAreRefused) {
  expect_refused("pointing.json", "/blocks", "4", "blocks", "non-negative integer");
  expect_refused("pointing.json", "/blocks", 0, "blocks", "from 1 to 100");
  expect_refused("pointing.json", "/repetitions", 2.5, "repetitions", "non-negative integer");
  expect_refused("pointing.json", "/seed", -1, "seed", "non-negative integer");
  expect_refused("pointing.json", "/biometrics/emg", 1, "biometrics.emg", "true or false");
  expect_refused("pointing.json", "/pointing/acquisitions", 0, "pointing.acquisitions", "from 1 to 20");
}

TEST(ProtocolErrors, UnknownChoicesListTheAllowedOnes) {
  expect_refused("pointing.json", "/kind", "fitts", "kind", "matching, pointing, list_selection, textures");
  expect_refused("pointing.json", "/order/scheme", "shuffled", "order.scheme", "random, latin_square, fixed");
  expect_refused("pointing.json", "/ratings/0/scale", "valence", "ratings[0].scale", "sam_valence");
  expect_refused("pointing.json", "/ratings/0/min_is", "negative", "ratings[0].min_is", "low, high");
}

TEST(ProtocolErrors, RatingRangesMustRunUpwards) {
  expect_refused("pointing.json", "/ratings/0/max", 1, "ratings[0].max", "above min");
}

TEST(ProtocolErrors, AScaleAskedTwiceIsRefused) {
  json file = example_json("pointing.json");
  file["ratings"].push_back(file["ratings"][0]);
  const Refusal r = refusal(file);
  EXPECT_EQ(r.path, "ratings[1].scale");
}

TEST(ProtocolErrors, DuplicateNamesAreRefused) {
  expect_refused("pointing.json", "/factors/0/levels/1/name", "not-rendered", "factors[0].levels[1].name",
                 "already");
  expect_refused("pointing.json", "/factors/2/name", "knob", "factors[2].name", "twice");
  expect_refused("pointing.json", "/factors/2/levels/0/name", "W 1.4", "factors[2].levels[0].name", "letters");
}

TEST(ProtocolErrors, PointingLevelsMustGiveTheirAmplitudeAndWidth) {
  expect_refused("pointing.json", "/factors/1/levels/1/parameters", json::object(),
                 "factors[1].levels[1].parameters.amplitude_deg", "required");
  expect_refused("pointing.json", "/factors/2/levels/0/parameters/width_deg", 0,
                 "factors[2].levels[0].parameters.width_deg", "above 0");
  expect_refused("pointing.json", "/pointing/width_factor", "amplitude", "pointing.width_factor", "another factor");
  expect_refused("pointing.json", "/pointing/amplitude_factor", "distance", "pointing.amplitude_factor",
                 "no factor named");
}

TEST(ProtocolErrors, ASectionForAnotherKindIsRefused) {
  json file = example_json("pointing.json");
  file["matching"] = example_json("matching-expert.json")["matching"];
  EXPECT_EQ(refusal(file).path, "matching");
}

TEST(ProtocolErrors, AnUnknownSimulatorPresetIsRefused) {
  expect_refused("pointing.json", "/factors/0/levels/0/preset", "study4-not-rendered", "factors[0].levels[0].preset",
                 "knoblab simulate --list");
}

TEST(ProtocolErrors, PracticeMustLeaveABlockToAnalyseAndUseOneForm) {
  expect_refused("pointing.json", "/practice/blocks", 4, "practice.blocks", "fewer than blocks");
  expect_refused("pointing.json", "/practice/trials", 2, "practice", "not both");
}

TEST(ProtocolErrors, ALatinSquareNeedsAFactorThatExists) {
  expect_refused("pointing.json", "/order", json{{"scheme", "latin_square"}}, "order.factor", "required");
  expect_refused("pointing.json", "/order", json{{"scheme", "latin_square"}, {"factor", "knobs"}}, "order.factor",
                 "no factor named \"knobs\"");
  expect_refused("pointing.json", "/order", json{{"scheme", "random"}, {"factor", "knob"}}, "order.factor",
                 "latin_square");
}

TEST(ProtocolErrors, StagesMustSplitTheConditions) {
  expect_refused("matching-novice.json", "/stages/1/levels/knob/0", "F", "stages[1].levels.knob[0]", "no level");
  expect_refused("matching-novice.json", "/stages/1/levels/knob", json{"C", "D"}, "stages", "every condition");
  expect_refused("matching-novice.json", "/stages/1/levels/knob", json{"B", "C", "D", "E"}, "stages[1]",
                 "shares conditions with stages[0]");
  expect_refused("matching-novice.json", "/stages/1/levels/knobs", json{"C"}, "stages[1].levels.knobs",
                 "unknown key");
}

TEST(ProtocolErrors, SlidersStayWithinTheKnobsLimitsAndStagesNameThem) {
  expect_refused("matching-novice.json", "/matching/sliders/0/max", 0.002, "matching.sliders[0].max", "0.0015");
  expect_refused("matching-novice.json", "/matching/sliders/2/parameter", "B_vel", "matching.sliders[2].parameter",
                 "second slider");
  expect_refused("matching-novice.json", "/matching/stage_sliders/with-detents/2", "P_pos",
                 "matching.stage_sliders.with-detents[2]", "no slider");
  expect_refused("matching-novice.json", "/matching/stage_sliders/without-detents", kRemove,
                 "matching.stage_sliders.without-detents", "required key is missing");
}

TEST(ProtocolErrors, ListSelectionAndTexturesSettingsAreChecked) {
  expect_refused("list-selection.json", "/list_selection/freeform_level", "explore", "list_selection.freeform_level",
                 "no level");
  expect_refused("list-selection.json", "/list_selection/items_per_rev", 0, "list_selection.items_per_rev",
                 "above 0");
  expect_refused("textures.json", "/textures/stroke_max_s", 2, "textures.stroke_max_s", "at least stroke_min_s");
  expect_refused("textures.json", "/textures/factor", "surface", "textures.factor", "no factor named");
}

TEST(ProtocolErrors, TextThatIsNotJsonIsRefusedAsAWhole) {
  try {
    parse_protocol_text("{\"study\": ");
    FAIL() << "accepted";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.path(), "");
    EXPECT_NE(std::string(e.what()).find("not JSON"), std::string::npos);
  }
  try {
    parse_protocol_text("[1, 2]");
    FAIL() << "accepted";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("expected an object"), std::string::npos);
  }
}

TEST(ProtocolErrors, AFilesErrorsNameTheFileAndKeepTheKeyPath) {
  const auto dir = std::filesystem::path(::testing::TempDir());
  const auto missing = dir / "knoblab-study-no-such-protocol.json";
  EXPECT_THROW(load_protocol(missing), ProtocolError);
  json file = example_json("textures.json");
  file["blocks"] = 0;
  const auto path = dir / ("knoblab-study-bad-" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << file.dump(2);
  try {
    load_protocol(path);
    FAIL() << "accepted";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.path(), "blocks");
    EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": blocks: ", 0), 0u) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(ProtocolErrors, AProtocolErrorIsAnInvalidArgument) {
  json file = example_json("textures.json");
  file["title"] = "";
  EXPECT_THROW(parse_protocol(file), std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::study
