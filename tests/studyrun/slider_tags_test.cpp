// The novices' words for each matching slider (thesis Table 15's sticky
// notes), kept as session notes tagged ["slider", parameter]: written by the
// familiarization before the first trial, once, only for novices, and read
// back per participant with the newest words per slider.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <set>

#include "knoblab/studyrun/session.hpp"
#include "knoblab/studyrun/simulated_participant.hpp"
#include "knoblab/studyrun/slider_tags.hpp"
#include "plant_apparatus.hpp"
#include "protocols.hpp"

namespace knoblab::test {
namespace {

using nlohmann::json;

struct Scratch {
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("knoblab-slider-tags-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  Scratch() { std::filesystem::create_directories(dir); }
  ~Scratch() { std::filesystem::remove_all(dir); }
  static inline int counter = 0;
};

// Counts what the runner asks the simulated participant for its slider words.
class Counting final : public studyrun::Participant {
 public:
  explicit Counting(studyrun::Participant& inner) : inner_(inner) {}
  void begin_trial(const study::Protocol& p, const study::Trial& t) override { inner_.begin_trial(p, t); }
  studyrun::Action act(const studyrun::Display& d, const studyrun::KnobReading& r) override { return inner_.act(d, r); }
  json rate(const std::vector<study::Rating>& s, const json& m) override { return inner_.rate(s, m); }
  std::map<std::string, std::string> slider_tags(const std::vector<study::Slider>& sliders) override {
    ++asked;
    return inner_.slider_tags(sliders);
  }
  int asked = 0;

 private:
  studyrun::Participant& inner_;
};

struct TagRun {
  Scratch scratch;
  store::Store db = store::Store::open(scratch.dir / "lab.sqlite");
  PlantApparatus apparatus;
  studyrun::SimulatedParticipant simulated{apparatus.hand(), studyrun::ParticipantModel{}, 7};
  Counting participant{simulated};
  studyrun::SessionResult run(const json& protocol, const std::string& code = "P01",
                              const studyrun::SessionOptions& o = {}) {
    return studyrun::run_session(db, study::parse_protocol(protocol), protocol.dump(), code, 0, apparatus,
                                 participant, o);
  }
};

// The words Table 15's novices wrote, a few per slider: the simulated
// participant's must be among them.
const std::map<std::string, std::set<std::string>> kTable15 = {
    {"M_acc", {"weight", "whoosh", "spinny", "spin faster", "momentum", "slingy", "inertia", "smooth, but heavy"}},
    {"B_vel", {"friction", "heavy", "like moving through mud", "spin slower & stops", "pudding", "buttery",
               "hard to turn", "stiffer"}},
    {"A_pos", {"bump size", "clicks", "bigness of detents", "really bumpy", "feeling bumps", "bump height", "wobbly",
               "big clicky"}},
    {"detents_per_rev", {"how many detents", "bump frequency", "spacing bumps", "# of bumps", "knobbly", "clicky",
                         "frequency of detents"}},
};

// "a, b" of one slider's vocabulary: either a word of it, or two.
bool from_table15(const std::string& parameter, const std::string& words) {
  const auto& v = kTable15.at(parameter);
  if (v.contains(words)) return true;
  for (const std::string& first : v)
    if (words.starts_with(first + ", ") && v.contains(words.substr(first.size() + 2))) return true;
  return false;
}

TEST(SliderTags, ASimulatedNoviceLabelsEverySliderOnceBeforeItsFirstTrial) {
  TagRun r;
  const auto result = r.run(shortened_matching_json());
  ASSERT_TRUE(result.finished);
  EXPECT_EQ(r.participant.asked, 1);
  const auto notes = r.db.study_notes(result.session_id);
  ASSERT_EQ(notes.size(), 4u);  // M_acc, B_vel, A_pos, detents_per_rev: every slider, not only the first stage's
  const auto trials = r.db.study_trials(result.session_id);
  ASSERT_FALSE(trials.empty());
  std::set<std::string> labelled;
  for (const store::StudyNote& n : notes) {
    EXPECT_FALSE(n.trial_index.has_value()) << n.text;
    const json tags = json::parse(n.tags_json);
    ASSERT_EQ(tags.size(), 2u) << n.tags_json;
    EXPECT_EQ(tags[0], "slider");
    const std::string parameter = tags[1];
    labelled.insert(parameter);
    EXPECT_TRUE(from_table15(parameter, n.text)) << parameter << ": " << n.text;
    EXPECT_LE(n.noted_unix, trials.front().started_unix) << "kept before the first trial";
    EXPECT_EQ(studyrun::slider_tag_parameter(n), parameter);
  }
  EXPECT_EQ(labelled, (std::set<std::string>{"A_pos", "B_vel", "M_acc", "detents_per_rev"}));
  // Read back for the study: the participant's four.
  const auto study = studyrun::slider_tags(r.db, "matching-short");
  ASSERT_EQ(study.size(), 1u);
  EXPECT_EQ(study.at("P01").size(), 4u);
  EXPECT_EQ(study.at("P01"), studyrun::session_slider_tags(r.db, result.session_id));
}

TEST(SliderTags, TheSameSeedGivesTheSameWordsAndTheTrialsAreAsWithoutThem) {
  TagRun a, b;
  const json protocol = shortened_matching_json();
  const auto first = a.run(protocol);
  const auto second = b.run(protocol);
  EXPECT_EQ(studyrun::session_slider_tags(a.db, first.session_id),
            studyrun::session_slider_tags(b.db, second.session_id));
  // The words come from a generator of their own: the trials' draws are
  // those of a participant never asked.
  Scratch scratch;
  store::Store db = store::Store::open(scratch.dir / "lab.sqlite");
  PlantApparatus apparatus;
  studyrun::SimulatedParticipant plain{apparatus.hand(), studyrun::ParticipantModel{}, 7};
  json expert_like = protocol;
  expert_like["matching"]["group"] = "expert";  // not asked for words
  const auto unasked = studyrun::run_session(db, study::parse_protocol(expert_like), expert_like.dump(), "P01", 0,
                                             apparatus, plain);
  const auto with = a.db.study_trials(first.session_id);
  const auto without = db.study_trials(unasked.session_id);
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t i = 0; i < with.size(); ++i) {
    EXPECT_EQ(json::parse(with[i].result_json)["sliders"], json::parse(without[i].result_json)["sliders"]) << i;
    EXPECT_EQ(with[i].ratings_json, without[i].ratings_json) << i;
  }
}

TEST(SliderTags, AResumedSessionIsNotAskedAgainAndKeepsItsFirstWords) {
  TagRun r;
  const json protocol = shortened_matching_json();
  studyrun::SessionOptions one;
  one.max_trials = 1;
  const auto first = r.run(protocol, "P01", one);
  ASSERT_FALSE(first.finished);
  ASSERT_EQ(r.db.study_notes(first.session_id).size(), 4u);
  const auto words = studyrun::session_slider_tags(r.db, first.session_id);
  const auto again = r.run(protocol);
  EXPECT_EQ(again.session_id, first.session_id);
  EXPECT_EQ(again.resumed_at, 2u);
  EXPECT_TRUE(again.finished);
  EXPECT_EQ(r.participant.asked, 1);
  EXPECT_EQ(r.db.study_notes(first.session_id).size(), 4u);
  EXPECT_EQ(studyrun::session_slider_tags(r.db, first.session_id), words);
}

TEST(SliderTags, ExpertsAndTheOtherKindsAreNotAskedAndStoreNone) {
  TagRun r;
  json expert = example_protocol("matching-expert");
  expert["study"] = "matching-expert-short";
  keep_levels(expert, "knob", {"A"});
  const auto e = r.run(expert);
  ASSERT_TRUE(e.finished);
  EXPECT_TRUE(r.db.study_notes(e.session_id).empty());
  const auto p = r.run(shortened_pointing_json(), "P02");
  ASSERT_TRUE(p.finished);
  EXPECT_TRUE(r.db.study_notes(p.session_id).empty());
  EXPECT_EQ(r.participant.asked, 0);
  EXPECT_TRUE(studyrun::slider_tags(r.db, "matching-expert-short").empty());
}

TEST(SliderTags, ALaterNoteForASliderReplacesTheEarlierAndOtherNotesAreNotTags) {
  Scratch scratch;
  store::Store db = store::Store::open(scratch.dir / "lab.sqlite");
  const json protocol = shortened_matching_json();
  const auto open = [&](const std::string& code, std::size_t index) {
    return db
        .open_study_session({.study = "matching-short", .participant = code, .participant_index = index,
                             .protocol_json = protocol.dump(), .plan_trials = 2})
        .session_id;
  };
  const std::int64_t p01 = open("P01", 0), p02 = open("P02", 1);
  studyrun::save_slider_tags(db, p01, {{"M_acc", "weight"}, {"B_vel", "  pudding "}, {"A_pos", "   "}});
  studyrun::save_slider_tags(db, p02, {{"detents_per_rev", "clicky"}});
  // The experimenter's notes that are not slider tags: about a trial, or tagged otherwise.
  const auto note = [&](std::optional<std::size_t> trial, const std::string& text, const std::string& tags) {
    db.add_study_note({.session_id = p01, .trial_index = trial, .text = text, .tags_json = tags});
  };
  note(1, "heavier", R"(["slider","M_acc"])");
  note(std::nullopt, "confused A and B", R"(["slider"])");
  note(std::nullopt, "x", R"(["slider","P_pos"])");
  note(std::nullopt, "think-aloud", "[]");
  EXPECT_EQ(studyrun::session_slider_tags(db, p01),
            (studyrun::SliderTags{{"B_vel", "pudding"}, {"M_acc", "weight"}}));
  // A correction: a new note, the newest wins.
  studyrun::save_slider_tags(db, p01, {{"M_acc", "momentum"}});
  const auto study = studyrun::slider_tags(db, "matching-short");
  EXPECT_EQ(study, (std::map<std::string, studyrun::SliderTags>{
                       {"P01", {{"B_vel", "pudding"}, {"M_acc", "momentum"}}},
                       {"P02", {{"detents_per_rev", "clicky"}}}}));
  // A parameter that is no slider's is refused before anything is written.
  const std::size_t notes = db.study_notes(p01).size();
  EXPECT_THROW(studyrun::save_slider_tags(db, p01, {{"A_pos", "bumps"}, {"P_pos", "clicks"}}), std::invalid_argument);
  EXPECT_EQ(db.study_notes(p01).size(), notes);
}

}  // namespace
}  // namespace knoblab::test
