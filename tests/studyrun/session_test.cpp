// Sessions run by the simulated participant on the simulated knob (in
// simulated time, tests/studyrun/plant_apparatus.hpp), into a real sqlite
// store: every trial committed with its measures, and a stopped session
// picked up where it stopped.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <numbers>
#include <optional>
#include <sstream>

#include "knoblab/study/plan.hpp"
#include "knoblab/studyrun/core_apparatus.hpp"
#include "knoblab/studyrun/export.hpp"
#include "knoblab/studyrun/session.hpp"
#include "knoblab/studyrun/simulated_participant.hpp"
#include "plant_apparatus.hpp"
#include "protocols.hpp"

namespace knoblab::test {
namespace {

using nlohmann::json;

struct Scratch {
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("knoblab-studyrun-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  Scratch() { std::filesystem::create_directories(dir); }
  ~Scratch() { std::filesystem::remove_all(dir); }
  static inline int counter = 0;
};

struct SessionRun {
  Scratch scratch;
  store::Store db = store::Store::open(scratch.dir / "lab.sqlite");
  PlantApparatus apparatus;
  studyrun::SimulatedParticipant participant{apparatus.hand(), studyrun::ParticipantModel{}, 7};
  studyrun::SessionResult run(const json& protocol, const studyrun::SessionOptions& o = {}) {
    return studyrun::run_session(db, study::parse_protocol(protocol), protocol.dump(), "P01", 0, apparatus,
                                 participant, o);
  }
};

std::vector<double> movement_times(const std::vector<store::StudyTrial>& trials, const std::string& width) {
  std::vector<double> out;
  for (const auto& t : trials) {
    const json measures = json::parse(t.result_json);
    if (json::parse(t.condition_json)["width"] == width)
      for (const auto& a : measures["acquisitions"]) out.push_back(a["movement_time_s"]);
  }
  return out;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

TEST(Session, ASimulatedParticipantCompletesShortenedPointingWithEveryTrialCommitted) {
  SessionRun r;
  const json protocol = shortened_pointing_json();
  const studyrun::SessionResult result = r.run(protocol);
  EXPECT_TRUE(result.finished);
  EXPECT_EQ(result.resumed_at, 1u);
  const auto trials = r.db.study_trials(result.session_id);
  ASSERT_EQ(trials.size(), 4u);  // 2 renderings × 2 widths
  ASSERT_EQ(result.trials_run, 4u);
  const study::Plan plan = study::plan(study::parse_protocol(protocol), "P01", 0);
  for (const store::StudyTrial& t : trials) {
    const json measures = json::parse(t.result_json);
    EXPECT_FALSE(measures["timed_out"].get<bool>()) << t.result_json;
    ASSERT_EQ(measures["acquisitions"].size(), 3u);
    for (const json& a : measures["acquisitions"]) {
      EXPECT_GT(a["movement_time_s"].get<double>(), 0.1) << a;
      EXPECT_LT(a["movement_time_s"].get<double>(), 5.0) << a;
      EXPECT_GE(a["overshoot_deg"].get<double>(), 0.0);
    }
    const json ratings = json::parse(t.ratings_json);
    ASSERT_TRUE(ratings.contains("appropriateness")) << t.ratings_json;
    EXPECT_GE(ratings["appropriateness"].get<int>(), 1);
    EXPECT_LE(ratings["appropriateness"].get<int>(), 9);
    // The 100 ms trace covers the trial.
    const json trace = json::parse(t.trace_json);
    EXPECT_GE(trace["t_s"].size(), 10u);
    EXPECT_NEAR(trace["t_s"][1].get<double>() - trace["t_s"][0].get<double>(), 0.1, 1.5e-3);
    // The condition is the plan's.
    const study::Trial& planned = plan.trials.at(t.trial_index - 1);
    EXPECT_EQ(json::parse(t.condition_json)["knob"],
              study::trial_level(study::parse_protocol(protocol), planned, 0).name);
  }
  EXPECT_TRUE(r.db.study_session(result.session_id)->finished_unix.has_value());
}

TEST(Session, TheSimulatedParticipantTakesLongerForTheNarrowTargetAsFittsLawSays) {
  SessionRun r;
  const json protocol = shortened_pointing_json();
  const auto result = r.run(protocol);
  const auto trials = r.db.study_trials(result.session_id);
  const double narrow = mean(movement_times(trials, "W1.4"));
  const double wide = mean(movement_times(trials, "W11.3"));
  EXPECT_GT(narrow, wide + 0.1) << "1.4°: " << narrow << " s, 11.3°: " << wide << " s";
}

TEST(Session, AStoppedSessionResumesAtTheTrialThatWasRunningAndKeepsWhatWasCommitted) {
  SessionRun r;
  const json protocol = shortened_pointing_json();
  std::atomic<bool> cancel{false};
  std::size_t committed = 0;
  studyrun::SessionOptions o;
  o.cancelled = [&] { return cancel.load(); };
  o.on_trial_committed = [&](const store::StudyTrial&) { ++committed; };
  // Stopped partway into the third trial, once its targets are showing.
  o.on_display = [&](const studyrun::Display& d) {
    if (committed == 2 && d.disk && d.disk->centre_rad != 0) cancel = true;
  };
  EXPECT_THROW(r.run(protocol, o), studyrun::Cancelled);
  const std::int64_t session = r.db.study_sessions("pointing-short").at(0).session_id;
  const auto before = r.db.study_trials(session);
  ASSERT_EQ(before.size(), 2u);
  EXPECT_EQ(r.db.next_study_trial(session), std::optional<std::size_t>(3));

  const studyrun::SessionResult again = r.run(protocol);
  EXPECT_EQ(again.session_id, session);
  EXPECT_EQ(again.resumed_at, 3u);
  EXPECT_EQ(again.trials_run, 2u);
  EXPECT_TRUE(again.finished);
  const auto after = r.db.study_trials(session);
  ASSERT_EQ(after.size(), 4u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(after[i].result_json, before[i].result_json);
    EXPECT_EQ(after[i].ratings_json, before[i].ratings_json);
    EXPECT_EQ(after[i].trace_json, before[i].trace_json);
  }
}

TEST(Session, MatchingMovesTheSlidersTowardsTheReferenceKnobAndRendersEachMove) {
  SessionRun r;
  const json protocol = shortened_matching_json();
  const auto result = r.run(protocol);
  ASSERT_TRUE(result.finished);
  const auto trials = r.db.study_trials(result.session_id);
  ASSERT_EQ(trials.size(), 2u);
  for (const auto& t : trials) {
    const json m = json::parse(t.result_json);
    EXPECT_FALSE(m["timed_out"].get<bool>());
    EXPECT_GE(m["slider_moves"].get<int>(), 1) << t.result_json;
    const std::string stage = t.stage;
    EXPECT_EQ(m["sliders"].size(), stage == "without-detents" ? 2u : 4u) << t.result_json;
    EXPECT_TRUE(json::parse(t.ratings_json).contains("satisfaction"));
  }
  // Knob A (the high-friction radio knob) is matched with friction, not nothing.
  const json a = json::parse(trials[0].result_json);
  EXPECT_EQ(a["reference"], "A");
  EXPECT_GT(a["sliders"]["B_vel"].get<double>(), 0.0);
  EXPECT_GT(r.apparatus.renders, 4) << "each slider move is rendered";
}

TEST(Session, ListSelectionExploresFreelyThenFindsEachTarget) {
  SessionRun r;
  const json protocol = shortened_list_json();
  const auto result = r.run(protocol);
  ASSERT_TRUE(result.finished);
  const auto trials = r.db.study_trials(result.session_id);
  ASSERT_EQ(trials.size(), 4u);
  for (const auto& t : trials) {
    const json m = json::parse(t.result_json);
    if (m["context"] == "freeform") {
      EXPECT_NEAR(m["exploration_s"].get<double>(), 1.5, 0.01);
    } else {
      EXPECT_TRUE(m["selected"].get<bool>()) << t.result_json;
      EXPECT_GT(m["time_s"].get<double>(), 0.3);
    }
    EXPECT_TRUE(json::parse(t.ratings_json).contains("sam_valence")) << t.ratings_json;
  }
}

TEST(Session, AStoreThatRanAnotherProtocolForTheParticipantIsRefusedNotMixed) {
  SessionRun r;
  json protocol = shortened_pointing_json();
  studyrun::SessionOptions o;
  o.max_trials = 1;
  r.run(protocol, o);
  protocol["title"] = "edited after the session began";
  EXPECT_ANY_THROW(r.run(protocol));
  EXPECT_EQ(r.db.study_trials(r.db.study_sessions("pointing-short").at(0).session_id).size(), 1u);
}

}  // namespace
}  // namespace knoblab::test

namespace knoblab::test {
namespace {

TEST(Session, RunsThroughHapticdsOwnCoreInSimulatedTimeWithTheRenderingFeltOnTheKnob) {
  Scratch scratch;
  store::Store db = store::Store::open(scratch.dir / "lab.sqlite");
  studyrun::CoreApparatus core;
  studyrun::SimulatedParticipant participant(core.hand(), studyrun::ParticipantModel{}, 11);
  const json protocol = shortened_pointing_json();
  const auto result = studyrun::run_session(db, study::parse_protocol(protocol), protocol.dump(), "P02", 1, core,
                                            participant);
  ASSERT_TRUE(result.finished);
  const auto trials = db.study_trials(result.session_id);
  ASSERT_EQ(trials.size(), 4u);
  // The heavy knob pushes back: the hand feels more torque with it than with none.
  double felt[2] = {0, 0};
  int n[2] = {0, 0};
  for (const auto& t : trials) {
    const json trace = json::parse(t.trace_json);
    const int heavy = json::parse(t.condition_json)["knob"] == "high-inertia" ? 1 : 0;
    for (const auto& tau : trace["torque_Nm"]) felt[heavy] += std::abs(tau.get<double>()), ++n[heavy];
    const json measures = json::parse(t.result_json);
    EXPECT_FALSE(measures["timed_out"].get<bool>()) << t.result_json;
  }
  EXPECT_GT(felt[1] / n[1], 1.5 * felt[0] / n[0]);
}

}  // namespace
}  // namespace knoblab::test

namespace knoblab::test {
namespace {

TEST(Session, TheTrialsExportHasOneColumnPerFactorMeasureAndRatingAndARowPerTrial) {
  SessionRun r;
  json protocol = example_protocol("textures");
  protocol["practice"] = json::object();
  keep_levels(protocol, "texture", {"FUR", "GLS", "OIL"});
  ASSERT_TRUE(r.run(protocol).finished);
  std::ostringstream csv;
  studyrun::write_trials_csv(csv, r.db, protocol["study"].get<std::string>());
  std::istringstream in(csv.str());
  std::string header, line;
  std::getline(in, header);
  // The texture is a factor and also what the task recorded: one column.
  EXPECT_EQ(header,
            "participant,session,block,trial,practice,stage,texture,started_unix,duration_s,onset_s,stroke_s,"
            "affect_grid_arousal,affect_grid_valence,emg_uV,sc_uS,capture_id");
  const auto columns = std::count(header.begin(), header.end(), ',');
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << line;
  }
  EXPECT_EQ(rows, 3);
}

}  // namespace
}  // namespace knoblab::test

namespace knoblab::test {
namespace {

// List selection's target finding turns the knob whole revolutions (a
// target three items away is three turns), and the knob keeps its angle from
// one trial to the next and from one participant to the next: there is no
// zero a hand goes back to.

// The first reach the participant asks for, in `trial`, of a knob at rest at
// `theta` with the display `d`; none in 2 s: nullopt.
std::optional<sim::HandCommand> first_reach(studyrun::SimulatedParticipant& participant, sim::HandChannel& hand,
                                            const study::Protocol& protocol, const study::Trial& trial,
                                            const studyrun::Display& d, double theta) {
  participant.begin_trial(protocol, trial);
  std::uint64_t seen = hand.sequence();
  sim::HandCommand c;
  for (int ms = 0; ms < 2000; ++ms) {
    participant.act(d, {ms * 1e-3, theta, 0, 0});
    if (hand.receive(seen, c)) return c;
  }
  return std::nullopt;
}

studyrun::Display display_off(const std::string& instruction) {
  studyrun::Display d;  // no counter, no target: before onset, or freeform exploration
  d.version = 1;
  d.instruction = instruction;
  return d;
}

const study::Trial& first_trial_of(const study::Protocol& protocol, const study::Plan& plan, const std::string& stage) {
  for (const study::Trial& t : plan.trials)
    if (protocol.stages.at(t.stage).name == stage) return t;
  throw std::logic_error("no trial of stage " + stage);
}

TEST(Session, TheSimulatedParticipantExploresTheKnobWhereItIsHoweverFarTargetFindingHasTurnedIt) {
  const study::Protocol protocol = shortened_list();
  const study::Plan plan = study::plan(protocol, "P01", 0);
  sim::HandChannel hand;
  const studyrun::ParticipantModel model;
  studyrun::SimulatedParticipant participant(hand, model, 7);
  const double theta = -20 * std::numbers::pi;  // ten turns from where the session began
  const auto reach = first_reach(participant, hand, protocol, first_trial_of(protocol, plan, "freeform"),
                                 display_off("Explore the knob"), theta);
  ASSERT_TRUE(reach.has_value());
  EXPECT_LE(std::abs(reach->target_rad - theta), 1.5) << "back and forth across where the knob is";
  EXPECT_LE(1.875 * std::abs(reach->target_rad - theta) / reach->duration_s, model.peak_speed_rad_s + 1e-9)
      << "no faster than a wrist turns";
}

TEST(Session, InTargetFindingTheSimulatedParticipantWaitsForTheCounterBeforeTurningTheKnob) {
  const study::Protocol protocol = shortened_list();
  const study::Plan plan = study::plan(protocol, "P01", 0);
  sim::HandChannel hand;
  studyrun::SimulatedParticipant participant(hand, studyrun::ParticipantModel{}, 7);
  const studyrun::Display before_onset = display_off("Turn the knob until the counter shows the target");
  EXPECT_FALSE(first_reach(participant, hand, protocol, first_trial_of(protocol, plan, "target-finding"), before_onset,
                           -20 * std::numbers::pi)
                   .has_value());
}

TEST(Session, ListSelectionThroughHapticdsOwnCoreKeepsTheKnobUnderTheVelocityLimitTrialAfterTrial) {
  Scratch scratch;
  store::Store db = store::Store::open(scratch.dir / "lab.sqlite");
  json protocol = example_protocol("list-selection");
  protocol["list_selection"]["exploration_s"] = 1.5;
  keep_levels(protocol, "knob", {"not-rendered"});  // with practice: four target-finding trials each
  // One knob for both participants, as `knoblab study simulate` has: the
  // second begins with the knob where the first left it, turns away.
  studyrun::CoreApparatus core;
  for (std::size_t index : {0u, 1u}) {
    const std::string code = "P0" + std::to_string(index + 1);
    studyrun::SimulatedParticipant participant(core.hand(), studyrun::ParticipantModel{}, 7 + index);
    const auto result = studyrun::run_session(db, study::parse_protocol(protocol), protocol.dump(), code, index,
                                              core, participant);  // throws ApparatusError on a fault
    participant.release();
    ASSERT_TRUE(result.finished) << code;
    std::size_t found = 0;
    for (const auto& t : db.study_trials(result.session_id)) {
      const json m = json::parse(t.result_json);
      if (m["context"] == "target") found += m["selected"].get<bool>() ? 1 : 0;
    }
    EXPECT_EQ(found, 4u) << code;
  }
}

}  // namespace
}  // namespace knoblab::test
