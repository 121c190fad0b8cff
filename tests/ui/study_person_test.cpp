// A matching session run from the screens as the experimenter and a person
// would, not by the simulated participant: the real window (offscreen)
// against hapticd on the sim backend, the session over HapticdApparatus and
// the PersonParticipant, a slider dragged with the mouse on the participant
// view, "done" and a rating tapped, a note and the slider tags typed in the
// experimenter view, and everything checked in the store (real sqlite)
// before the session is stopped and resumed.
#include <gtest/gtest.h>

#include <QPointF>
#include <QTest>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "kiosk.hpp"
#include "knoblab/store/store.hpp"
#include "process.hpp"

namespace knoblab::ui {
namespace {

using nlohmann::json;

// The novices' protocol cut to one knob per stage, once each (two trials),
// the friction slider perceptual (β = 0.5: value = min + span·position²),
// the inertia slider linear.
json person_protocol() {
  std::ifstream in(std::string(KNOBLAB_STUDY_EXAMPLES_DIR) + "/matching-novice.json");
  json p = json::parse(in);
  p["study"] = "matching-person";
  p["repetitions"] = 1;
  json levels = json::array();
  for (const json& level : p["factors"][0]["levels"])
    if (level["name"] == "A" || level["name"] == "C") levels.push_back(level);
  p["factors"][0]["levels"] = levels;
  p["stages"][0]["levels"]["knob"] = {"A"};
  p["stages"][1]["levels"]["knob"] = {"C"};
  p["matching"]["sliders"][1]["perceptual_exponent"] = 0.5;
  return p;
}

// Drags a slider's handle with the mouse to `fraction` of its width, in
// steps as a finger moves; false when the slider is not on screen.
bool drag_slider(QQuickWindow* window, QQuickItem* slider, double fraction) {
  if (!slider) return false;
  Screen::settle(slider);
  const auto* handle = slider->property("handle").value<QQuickItem*>();
  if (!handle) return false;
  const QPointF from = handle->mapToScene(QPointF(handle->width() / 2, handle->height() / 2));
  const QPointF to = slider->mapToScene(QPointF(slider->width() * fraction, slider->height() / 2));
  QTest::mousePress(window, Qt::LeftButton, Qt::NoModifier, from.toPoint());
  for (int k = 1; k <= 10; ++k) {
    QTest::mouseMove(window, (from + (to - from) * (k / 10.0)).toPoint());
    Screen::wait(30);
  }
  QTest::mouseRelease(window, Qt::LeftButton, Qt::NoModifier, to.toPoint());
  Screen::wait(100);
  return true;
}

// The experimenter's way back from the participant view: the top-left corner held 2 s.
void hold_corner(QQuickWindow* window) {
  QTest::mousePress(window, Qt::LeftButton, Qt::NoModifier, QPoint(10, 10));
  Screen::wait(2400);
  QTest::mouseRelease(window, Qt::LeftButton, Qt::NoModifier, QPoint(10, 10));
  Screen::wait(300);
}

// A tap once the screen it is on has slid in.
bool tap_settled(const Screen& screen, const QString& name) {
  if (QQuickItem* i = screen.item(name)) Screen::settle(i);
  return screen.tap(name);
}

TEST(StudyPersonPath,
     ASliderMovedByTouchSetsTheMappedValueAndTheTrialIsStoredWithItsRatingAndNotesThenItResumesAtTheNextTrial) {
  g_warnings.clear();
  const std::string ring = "/knoblab-ui-person-" + std::to_string(::getpid());
  test::Hapticd daemon(ring);
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  const std::filesystem::path studies = std::filesystem::path(daemon.dir()) / "studies";
  std::filesystem::create_directories(studies);
  test::write_file(studies / "matching-person.json", person_protocol().dump(2));

  Kiosk kiosk(daemon, "home", QSize(1024, 600), QString::fromStdString(studies.string()));
  ASSERT_NE(kiosk.window, nullptr);
  StudySession& study = kiosk.study;
  QQuickWindow* window = kiosk.window;
  Screen screen(window);
  ASSERT_TRUE(spin_until([&] { return kiosk.link.connected(); })) << daemon.log();

  // The experimenter opens the user study and starts P11's session of the one protocol offered.
  ASSERT_TRUE(spin_until([&] { return tap_settled(screen, "studyButton"); }, 10000));
  ASSERT_TRUE(spin_until([&] { return screen.text("protocolTitle").startsWith("Haptic matching"); }, 10000));
  screen.type("participantCode", "P11");
  ASSERT_TRUE(tap_settled(screen, "startButton"));
  ASSERT_TRUE(spin_until([&] {
    return study.state() == "running" && study.trial() == 1 && !study.sliderRanges().isEmpty();
  }))
      << study.state().toStdString() << " " << study.message().toStdString() << " / "
      << kiosk.messages.join(" | ").toStdString();
  EXPECT_EQ(study.sliderRanges().size(), 2);  // the first stage: inertia and friction

  // The novice's words for each slider, typed by the experimenter from the sticky notes.
  ASSERT_TRUE(tap_settled(screen, "sliderTagsButton"));
  ASSERT_TRUE(spin_until([&] { return screen.shows("sliderTag.detents_per_rev.input"); }, 5000));
  const std::map<std::string, std::string> words = {
      {"M_acc", "momentum"}, {"B_vel", "pudding"}, {"A_pos", "bump size"}, {"detents_per_rev", "bump frequency"}};
  for (const auto& [parameter, text] : words)
    screen.type(QString::fromStdString("sliderTag." + parameter), QString::fromStdString(text));
  screen.shoot("study-slider-tags-1024x600");
  ASSERT_TRUE(tap_settled(screen, "saveSliderTags"));
  ASSERT_TRUE(spin_until([&] { return study.sliderTags().size() == 4; }, 10000))
      << kiosk.messages.join(" | ").toStdString();
  ASSERT_TRUE(tap_settled(screen, "closeSliderTags"));

  // The participant's view: the person drags the friction and inertia sliders.
  ASSERT_TRUE(tap_settled(screen, "participantViewButton"));
  ASSERT_TRUE(spin_until([&] { return screen.shows("slider.B_vel") && screen.shows("slider.M_acc"); }, 10000));
  ASSERT_TRUE(drag_slider(window, screen.item("slider.B_vel"), 0.6));
  ASSERT_TRUE(drag_slider(window, screen.item("slider.M_acc"), 0.4));
  const double b = screen.item("slider.B_vel")->property("value").toDouble();
  const double m = screen.item("slider.M_acc")->property("value").toDouble();
  ASSERT_GT(b, 0.2) << "the drag did not move the slider";
  ASSERT_LT(b, 0.9);
  ASSERT_GT(m, 0.1);
  // The session gets the value at the slider's position by the power law:
  // friction 0 → 30 mN·m/(rad/s) with β = 0.5 is 30·position², inertia
  // 0 → 0.75 mN·m/(rad/s²) linear is 0.75·position (presentation units).
  const double friction = 30 * b * b, inertia = 0.75 * m;
  ASSERT_TRUE(spin_until([&] {
    const QVariantMap s = study.sliders();
    return std::abs(s.value("B_vel").toDouble() - friction) < 1e-9 &&
           std::abs(s.value("M_acc").toDouble() - inertia) < 1e-9;
  }, 10000)) << "the session has friction " << study.sliders().value("B_vel").toDouble() << ", inertia "
             << study.sliders().value("M_acc").toDouble() << "; the sliders' positions map to " << friction << ", "
             << inertia;
  EXPECT_GT(std::abs(friction - 30 * b), 1.0) << "a linear slider would have set the same";
  // The value shown beside the slider is the mapped one.
  EXPECT_EQ(screen.text("sliderValue.B_vel"),
            QString::number(friction, 'f', friction >= 10 ? 1 : 2) + QStringLiteral(" mN·m/(rad/s)"));
  screen.shoot("study-person-sliders-1024x600");

  // "It feels the same", then the satisfaction rating, tapped.
  ASSERT_TRUE(tap_settled(screen, "matchedButton"));
  ASSERT_TRUE(spin_until([&] { return study.state() == "rating" && screen.shows("rate.3"); }, 10000))
      << study.state().toStdString();
  ASSERT_TRUE(tap_settled(screen, "rate.3"));
  ASSERT_TRUE(spin_until([&] { return study.committed() == 1 && study.trial() == 2; }, 20000))
      << study.state().toStdString() << " / " << kiosk.messages.join(" | ").toStdString();

  // Back in the experimenter view, a note with tags on the running trial.
  hold_corner(window);
  ASSERT_TRUE(spin_until([&] { return screen.shows("participantViewButton"); }, 5000));
  screen.type("note", "matched by friction alone");
  screen.type("tags", "friction, confident");
  ASSERT_TRUE(tap_settled(screen, "keepNote"));
  ASSERT_TRUE(spin_until([&] { return kiosk.messages.contains("Note kept with trial 2"); }, 10000))
      << kiosk.messages.join(" | ").toStdString();

  // The store holds the trial, its rating, the note and the slider tags.
  {
    store::Store db = store::Store::open(daemon.db());
    const auto sessions = db.study_sessions("matching-person");
    ASSERT_EQ(sessions.size(), 1u);
    EXPECT_EQ(sessions[0].participant, "P11");
    EXPECT_FALSE(sessions[0].simulated);
    const auto trials = db.study_trials(sessions[0].session_id);
    ASSERT_EQ(trials.size(), 1u);
    EXPECT_EQ(trials[0].trial_index, 1u);
    EXPECT_EQ(json::parse(trials[0].condition_json), (json{{"knob", "A"}}));
    EXPECT_EQ(json::parse(trials[0].ratings_json), (json{{"satisfaction", 3}}));
    const json result = json::parse(trials[0].result_json);
    EXPECT_NEAR(result["sliders"]["B_vel"].get<double>(), 30e-3 * b * b, 1e-12) << result;  // SI
    EXPECT_NEAR(result["sliders"]["M_acc"].get<double>(), 0.75e-3 * m, 1e-12) << result;
    EXPECT_FALSE(result["timed_out"].get<bool>());
    EXPECT_TRUE(trials[0].capture_id.has_value()) << "hapticd recorded the trial";
    std::map<std::string, std::string> tagged;
    int notes = 0;
    for (const store::StudyNote& n : db.study_notes(sessions[0].session_id)) {
      const json tags = json::parse(n.tags_json);
      if (!n.trial_index && tags.size() == 2 && tags[0] == "slider") {
        tagged[tags[1].get<std::string>()] = n.text;
      } else {
        ++notes;
        EXPECT_EQ(n.trial_index, std::optional<std::size_t>(2));
        EXPECT_EQ(n.text, "matched by friction alone");
        EXPECT_EQ(tags, (json{"friction", "confident"}));
      }
    }
    EXPECT_EQ(notes, 1);
    EXPECT_EQ(tagged, words);
  }

  // Stopped mid-trial 2 and started again: it resumes at trial 2, the words kept.
  ASSERT_TRUE(tap_settled(screen, "stopButton"));
  ASSERT_TRUE(spin_until([&] { return study.state() == "stopped"; }, 10000)) << study.state().toStdString();
  ASSERT_TRUE(spin_until([&] { return tap_settled(screen, "startButton"); }, 5000));
  ASSERT_TRUE(spin_until([&] { return study.state() == "running" && study.resumedAt() == 2 && study.trial() == 2; }))
      << study.state().toStdString() << " resumed at " << study.resumedAt() << " / "
      << kiosk.messages.join(" | ").toStdString();
  EXPECT_TRUE(kiosk.messages.contains("P11 resumes at trial 2 of 2")) << kiosk.messages.join(" | ").toStdString();
  EXPECT_EQ(study.sliderRanges().size(), 4);  // the second stage: all four sliders
  ASSERT_TRUE(spin_until([&] { return study.sliderTags().size() == 4; }, 5000));
  EXPECT_EQ(study.sliderTags().value("B_vel").toString(), "pudding");
  {
    store::Store db = store::Store::open(daemon.db());
    EXPECT_EQ(db.study_trials(db.study_sessions("matching-person").at(0).session_id).size(), 1u);
  }
  ASSERT_TRUE(tap_settled(screen, "stopButton"));
  ASSERT_TRUE(spin_until([&] { return study.state() == "stopped"; }, 10000));
  EXPECT_TRUE(g_warnings.isEmpty()) << g_warnings.join("\n").toStdString();
}

}  // namespace
}  // namespace knoblab::ui
