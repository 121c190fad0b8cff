// Every example protocol parses, and says what the thesis says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>

#include "examples.hpp"
#include "knoblab/sim/presets.hpp"

namespace knoblab::study {
namespace {

using test::example;

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Examples, EveryFileInTheExamplesFolderParses) {
  std::set<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(KNOBLAB_STUDY_EXAMPLES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    found.insert(entry.path().filename().string());
    EXPECT_NO_THROW(load_protocol(entry.path())) << entry.path();
  }
  for (const auto& name : test::example_names()) EXPECT_TRUE(found.contains(name)) << name;
}

TEST(Examples, PointingHasTable20sSevenRenderingsInSi) {
  const Protocol p = example("pointing.json");
  EXPECT_EQ(p.kind, Kind::Pointing);
  const Factor& knob = p.factors.at(0);
  ASSERT_EQ(knob.levels.size(), 7u);
  // Table 20 (mN·m, mN·m/(rad/s), mN·m/(rad/s²)) in SI.
  const Rendering expected[] = {{0, 0, 0, 0},      {0, 2.6e-3, 0, 0}, {0, 7.9e-3, 0, 0},     {0.06e-3, 0, 0, 0},
                                {0.21e-3, 0, 0, 0}, {0, 0, 7e-3, 1},   {0, 0, 19e-3, 5}};
  for (std::size_t i = 0; i < 7; ++i) {
    ASSERT_TRUE(knob.levels[i].rendering) << knob.levels[i].name;
    EXPECT_EQ(*knob.levels[i].rendering, expected[i]) << knob.levels[i].name;
  }
}

TEST(Examples, PointingTargetsAre30And200DegreesWide1Point4And11Point3) {
  const Protocol p = example("pointing.json");
  const auto& s = std::get<PointingSettings>(p.settings);
  EXPECT_EQ(s.acquisitions, 3u);
  const Factor& amplitude = p.factors.at(s.amplitude_factor);
  const Factor& width = p.factors.at(s.width_factor);
  ASSERT_EQ(amplitude.levels.size(), 2u);
  ASSERT_EQ(width.levels.size(), 2u);
  EXPECT_DOUBLE_EQ(*amplitude.levels[0].amplitude_rad, 30 * kDeg);
  EXPECT_DOUBLE_EQ(*amplitude.levels[1].amplitude_rad, 200 * kDeg);
  EXPECT_DOUBLE_EQ(*width.levels[0].width_rad, 1.4 * kDeg);
  EXPECT_DOUBLE_EQ(*width.levels[1].width_rad, 11.3 * kDeg);
}

TEST(Examples, PointingRunsFourBlocksOf28WithTheFirstAsPracticeAndRatesAppropriateness) {
  const Protocol p = example("pointing.json");
  EXPECT_EQ(p.blocks, 4u);
  EXPECT_EQ(p.repetitions, 1u);
  EXPECT_EQ(p.practice.blocks, 1u);
  EXPECT_EQ(p.order.scheme, OrderScheme::Random);
  ASSERT_EQ(p.stages.size(), 1u);
  std::size_t conditions = 1;
  for (const Factor& f : p.factors) conditions *= f.levels.size();
  EXPECT_EQ(conditions, 28u);
  ASSERT_EQ(p.ratings.size(), 1u);
  EXPECT_EQ(p.ratings[0].scale, Scale::Appropriateness);
  EXPECT_EQ(p.ratings[0].min, 1);
  EXPECT_EQ(p.ratings[0].max, 9);
  // Study 3's scale is the original SAM's way round: 1 is the favourable end.
  EXPECT_EQ(p.ratings[0].min_is, ScaleEnd::High);
  EXPECT_TRUE(p.biometrics.emg);
  EXPECT_TRUE(p.biometrics.sc);
}

TEST(Examples, MatchingSlidersAreTable11InSi) {
  for (const char* name : {"matching-novice.json", "matching-expert.json"}) {
    const Protocol p = example(name);
    const auto& m = std::get<MatchingSettings>(p.settings);
    ASSERT_EQ(m.sliders.size(), 4u) << name;
    EXPECT_EQ(m.sliders[0].parameter, "M_acc");
    EXPECT_DOUBLE_EQ(m.sliders[0].max, 0.75e-3);
    EXPECT_EQ(m.sliders[1].parameter, "B_vel");
    EXPECT_DOUBLE_EQ(m.sliders[1].max, 30e-3);
    EXPECT_EQ(m.sliders[2].parameter, "A_pos");
    EXPECT_DOUBLE_EQ(m.sliders[2].max, 15e-3);
    EXPECT_EQ(m.sliders[3].parameter, "detents_per_rev");
    EXPECT_DOUBLE_EQ(m.sliders[3].max, 32);
    for (const Slider& s : m.sliders) EXPECT_EQ(s.min, 0.0) << s.parameter;
    EXPECT_EQ(p.ratings.at(0).scale, Scale::Satisfaction);
    EXPECT_EQ(p.ratings.at(0).min_is, ScaleEnd::High);  // 1 = strongly agree
    EXPECT_EQ(p.factors.at(0).levels.size(), 5u);
  }
}

TEST(Examples, NovicesMatchTwoKnobsWithTwoSlidersThenThreeWithFourThreeTimesEach) {
  const Protocol p = example("matching-novice.json");
  const auto& m = std::get<MatchingSettings>(p.settings);
  EXPECT_EQ(m.group, MatchingSettings::Group::Novice);
  EXPECT_FALSE(m.think_aloud);
  EXPECT_EQ(p.repetitions, 3u);
  ASSERT_EQ(p.stages.size(), 2u);
  EXPECT_EQ(p.stages[0].allowed[0], (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(p.stages[1].allowed[0], (std::vector<std::size_t>{2, 3, 4}));
  EXPECT_EQ(m.stage_sliders[0], (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(m.stage_sliders[1], (std::vector<std::size_t>{0, 1, 2, 3}));
}

TEST(Examples, ExpertsMatchAllFiveKnobsOnceWithAllSlidersThinkingAloud) {
  const Protocol p = example("matching-expert.json");
  const auto& m = std::get<MatchingSettings>(p.settings);
  EXPECT_EQ(m.group, MatchingSettings::Group::Expert);
  EXPECT_TRUE(m.think_aloud);
  EXPECT_TRUE(m.explain_physics);
  EXPECT_EQ(p.repetitions, 1u);
  EXPECT_EQ(p.blocks, 1u);
  ASSERT_EQ(m.stage_sliders.size(), 1u);
  EXPECT_EQ(m.stage_sliders[0].size(), 4u);
}

TEST(Examples, ListSelectionHasTable19sSevenStimuliAndRatesSamValenceLowAtOne) {
  const Protocol p = example("list-selection.json");
  const Factor& knob = p.factors.at(1);
  ASSERT_EQ(knob.levels.size(), 7u);
  const Rendering expected[] = {{0, 0, 0, 0},      {0, 2.6e-3, 0, 0}, {0, 5.3e-3, 0, 0},    {0.06e-3, 0, 0, 0},
                                {0.38e-3, 0, 0, 0}, {0, 0, 14e-3, 1},  {0, 0, 14e-3, 3}};
  for (std::size_t i = 0; i < 7; ++i) EXPECT_EQ(*knob.levels[i].rendering, expected[i]) << knob.levels[i].name;
  ASSERT_EQ(p.ratings.size(), 1u);
  EXPECT_EQ(p.ratings[0].scale, Scale::SamValence);
  EXPECT_EQ(p.ratings[0].min_is, ScaleEnd::Low);
  const auto& s = std::get<ListSelectionSettings>(p.settings);
  EXPECT_EQ(p.factors.at(s.context_factor).levels.at(s.freeform_level).name, "freeform");
  ASSERT_EQ(p.stages.size(), 2u);
  EXPECT_EQ(p.stages[0].name, "freeform");
}

TEST(Examples, TexturesAreTable16sTwelveSurfacesRatedOnTheAffectGrid) {
  const Protocol p = example("textures.json");
  const auto& s = std::get<TexturesSettings>(p.settings);
  const Factor& textures = p.factors.at(s.factor);
  std::vector<std::string> labels;
  for (const Level& l : textures.levels) labels.push_back(l.name);
  EXPECT_EQ(labels, (std::vector<std::string>{"FUR", "GEL", "PTY", "SND", "ACR", "GLS", "BSH", "WD", "OIL", "STK",
                                              "HND", "SLK"}));
  EXPECT_EQ(textures.levels[9].description, "Double-sided sticky tape on an acrylic sheet");
  EXPECT_EQ(p.ratings.at(0).scale, Scale::AffectGrid);
  EXPECT_EQ(p.practice.trials, 12u);
  EXPECT_TRUE(s.blindfold);
}

// A level that cites a simulator preset renders what that preset simulates:
// the preset's inertia includes the haptic knob's own mechanism (§3.3.2).
TEST(Examples, RenderingsAgreeWithTheSimulatorPresetsTheyCite) {
  std::size_t checked = 0;
  for (const auto& name : test::example_names()) {
    const Protocol p = example(name);
    for (const Factor& f : p.factors)
      for (const Level& l : f.levels) {
        if (l.preset.empty() || !l.rendering) continue;
        const sim::presets::Preset* preset = sim::presets::find(l.preset);
        ASSERT_NE(preset, nullptr) << l.preset;
        const auto& k = preset->knob;
        const Rendering& r = *l.rendering;
        EXPECT_NEAR(k.inertia.M - sim::presets::kHapticKnobInertia, r.M_acc, 1e-12) << name << " " << l.name;
        EXPECT_NEAR(k.friction.B_pos, r.B_vel, 1e-12) << name << " " << l.name;
        EXPECT_NEAR(k.friction.B_neg, r.B_vel, 1e-12) << name << " " << l.name;
        EXPECT_NEAR(k.detents.A, r.A_pos, 1e-12) << name << " " << l.name;
        if (r.A_pos > 0) {
          EXPECT_NEAR(1.0 / k.detents.P, r.detents_per_rev, 1e-9) << name << " " << l.name;
        }
        ++checked;
      }
  }
  EXPECT_EQ(checked, 14u);  // Table 19's and Table 20's seven each
}

}  // namespace
}  // namespace knoblab::study
