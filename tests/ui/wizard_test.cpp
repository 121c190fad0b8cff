// The capture wizard driven by touch, end to end, against hapticd on the sim
// backend: taps on the real screens (offscreen), a sensor check, a capture
// with live traces, then the fit and the discrepancy run the wizard starts.
// What it shows must be what the CLI computes for the same capture, and all
// of it must be in the library.
#include <gtest/gtest.h>

#include <QGuiApplication>
#include <QInputMethod>
#include <QJSEngine>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "kiosk.hpp"
#include "process.hpp"

namespace knoblab::ui {
namespace {

// At both panel sizes the appliance is designed for: each step's screen is kept.
class CaptureWizard : public ::testing::TestWithParam<QSize> {};

TEST_P(CaptureWizard, DrivenByTouchItCapturesFitsFindsAndStoresWhatTheCliWould) {
  const QSize panel = GetParam();
  const std::string size = std::to_string(panel.width()) + "x" + std::to_string(panel.height());
  g_warnings.clear();
  const std::string ring = "/knoblab-ui-wizard-" + std::to_string(::getpid());
  // At the rate the camera's PID is tuned for (the tests' gentle 1 kHz makes
  // the simulated capture chatter); no overrun fault on this non-realtime host.
  test::Hapticd daemon(ring, {"--rate", "5000"});
  ASSERT_TRUE(daemon.ready()) << daemon.log();

  Kiosk kiosk(daemon, "home", panel);
  ASSERT_NE(kiosk.window, nullptr);
  DaemonLink& link = kiosk.link;
  KnobLibrary& knobs = kiosk.knobs;
  const QStringList& messages = kiosk.messages;
  QQuickWindow* window = kiosk.window;
  Screen screen(window);
  ASSERT_TRUE(spin_until([&] { return link.connected() && !link.telemetryName().isEmpty(); })) << daemon.log();

  // Home → the wizard; mounted in the lab.
  ASSERT_TRUE(spin_until([&] { return screen.tap("captureButton"); }));
  ASSERT_TRUE(spin_until([&] { return screen.tap("mountTripod"); }));
  screen.shoot("capture-1-mounting-" + size);
  ASSERT_TRUE(screen.tap("mountLab"));
  ASSERT_TRUE(screen.tap("next"));
  // The knob and its gripper.
  ASSERT_TRUE(spin_until([&] { return screen.shows("knobName.input"); }));
  // A tap on the field brings up the on-screen keyboard, and its keys type.
  ASSERT_TRUE(screen.tap("knobName.input"));
  ASSERT_TRUE(spin_until([&] { return screen.item("keyboard") && screen.item("keyboard")->property("active").toBool(); }))
      << "no on-screen keyboard: field focused " << screen.item("knobName.input")->hasActiveFocus() << ", input method visible "
      << QGuiApplication::inputMethod()->isVisible() << ", keyboard item " << (screen.item("keyboard") != nullptr)
      << ", platform input context " << (QGuiApplication::platformName().toStdString());
  ASSERT_TRUE(screen.type_on_keyboard("knob"));
  EXPECT_EQ(screen.text("knobName.input"), "knob");
  screen.type("knobName", "wizard-knob");
  screen.type("gripper", "ABS print, VHB tape");
  screen.shoot("capture-2-knob-" + size);
  ASSERT_TRUE(spin_until([&] { return screen.tap("next"); }));
  // Off the form, the keyboard goes down again.
  EXPECT_TRUE(spin_until([&] { return !screen.shows("keyboard"); }, 5000));
  // The sensor check (Table 4) runs and reports.
  ASSERT_TRUE(spin_until([&] { return screen.tap("verifySensors"); }));
  ASSERT_TRUE(spin_until([&] { return screen.shows("table4.theta"); })) << messages.join(" | ").toStdString();
  EXPECT_TRUE(screen.text("table4.theta").startsWith("angle: commanded − measured"))
      << screen.text("table4.theta").toStdString();
  ASSERT_TRUE(spin_until([&] { return link.mode() == "idle"; }));
  screen.shoot("capture-3-sensors-" + size);
  ASSERT_TRUE(screen.tap("next"));
  // The capture, with the angle and torque live, started as in the field by
  // the camera's capture button: hapticd's `capture_button` event.
  ASSERT_TRUE(spin_until([&] { return screen.shows("startCapture"); }));
  Screen::wait(300);
  emit link.event("capture_button", {{"presses", 1}, {"new", 1}});
  ASSERT_TRUE(spin_until([&] { return link.mode() == "capture"; })) << messages.join(" | ").toStdString();
  EXPECT_EQ(screen.text("startCapture"), "Capturing…");
  ASSERT_TRUE(spin_until([&] { return screen.item("angleTrace") && screen.item("angleTrace")->property("drawn").toInt() > 100; }))
      << "no live angle trace";
  EXPECT_GT(screen.item("torqueTrace")->property("drawn").toInt(), 100);
  Screen::wait(1500);  // a few seconds of trace
  screen.shoot("capture-4-capture-" + size);
  // Then the fit and the discrepancy run, by themselves.
  ASSERT_TRUE(spin_until([&] { return screen.text("resultState").startsWith("Saved in the library"); }, 180000))
      << screen.text("resultState").toStdString() << " / " << messages.join(" | ").toStdString();
  // The library re-read after each job: the fit, then the findings (or why there are none).
  ASSERT_TRUE(spin_until([&] {
    return screen.shows("param.A_pos") &&
           (screen.shows("finding.0") || screen.text("discrepancyNone").startsWith("No finding"));
  }));
  Screen::wait(4500);  // the message bar's news fades
  screen.shoot("capture-5-results-" + size);
  const int capture = static_cast<int>(screen.text("resultState").split(' ')[5].toInt());
  ASSERT_GT(capture, 0) << screen.text("resultState").toStdString();

  // The CLI on the same capture: the same numbers, shown the way the screen shows them.
  test::ScratchDir dir;
  // (With the report, as the UI runs it: the library's latest fit is this one.)
  const auto fit = test::run_knoblab({"fit", "--capture", std::to_string(capture), "--db", daemon.db(), "--json",
                                      (dir / "fit.json").string(), "--report", (dir / "report").string(), "--format",
                                      "png", "--dpi", "50"});
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto disc = test::run_knoblab({"discrepancy", "--capture", std::to_string(capture), "--db", daemon.db(),
                                       "--json", (dir / "d.json").string()});
  ASSERT_EQ(disc.exit_code, 0) << disc.err;
  const nlohmann::json cli_fit = nlohmann::json::parse(test::read_file(dir / "fit.json"));
  const nlohmann::json cli_disc = nlohmann::json::parse(test::read_file(dir / "d.json"));
  QJSEngine js;
  const QJSValue format = js.importModule(":/qt/qml/Knoblab/Ui/format.mjs");
  ASSERT_FALSE(format.isError()) << format.toString().toStdString();
  for (const auto& [name, value] : cli_fit["params"].items()) {
    const QJSValue shown = format.property("param").call(
        {QJSValue(QString::fromStdString(name)), QJSValue(value.get<double>()), QJSValue::UndefinedValue});
    EXPECT_EQ(screen.text(QString::fromStdString("param." + name)), shown.property("value").toString()) << name;
  }
  const auto& findings = cli_disc["findings"];
  for (std::size_t k = 0; k < findings.size(); ++k)
    EXPECT_TRUE(screen.text(QString("finding.%1").arg(k)).startsWith(QString::fromStdString(findings[k]["effect"])))
        << k << ": the screen says '" << screen.text(QString("finding.%1").arg(k)).toStdString() << "', the CLI "
        << findings[k]["effect"];
  EXPECT_EQ(screen.shows(QString("finding.%1").arg(findings.size())), false);
  if (findings.empty()) {
    EXPECT_TRUE(screen.shows("discrepancyNone"));
  }

  // In the library: the capture under the knob's name, lab-mounted, its gripper, its results.
  knobs.refresh();
  ASSERT_TRUE(spin_until([&] { return !knobs.loading(); }));
  const QVariantMap e = knobs.entry(capture);
  EXPECT_EQ(e.value("knob").toString(), "wizard-knob");
  EXPECT_EQ(e.value("mounting").toString(), "lab");
  EXPECT_EQ(e.value("gripper").toString(), "ABS print, VHB tape");
  EXPECT_EQ(e.value("status").toString(), "complete");
  EXPECT_FALSE(e.value("fit").isNull());
  EXPECT_FALSE(e.value("discrepancy").isNull());

  // "Feel it" from the library: the fit's stored render model, rendered on the knob.
  ASSERT_TRUE(screen.tap("openLibrary"));
  ASSERT_TRUE(spin_until([&] { return screen.text("knobTitle") == "wizard-knob"; }));
  // The library re-read (the CLI's results above) settles the layout first.
  knobs.refresh();
  ASSERT_TRUE(spin_until([&] { return !knobs.loading(); }));
  Screen::wait(1000);
  ASSERT_TRUE(spin_until([&] { return screen.tap("feelButton"); }));
  EXPECT_TRUE(spin_until([&] { return link.mode() == "render"; }))
      << messages.join(" | ").toStdString() << " / button: " << screen.text("feelButton").toStdString() << " at "
      << screen.item("feelButton")->mapToScene(QPointF(0, 0)).y() << ", warnings: " << g_warnings.join(" | ").toStdString();
  EXPECT_EQ(screen.text("feelState"), "The knob renders this fit (Eq. 14): turn it.");
  ASSERT_TRUE(screen.tap("feelButton"));
  EXPECT_TRUE(spin_until([&] { return link.mode() == "idle"; }));
  EXPECT_TRUE(g_warnings.isEmpty()) << g_warnings.join("\n").toStdString();
  ::shm_unlink(ring.c_str());
}

// On a tripod the camera's unbalance torque depends on its tilt: the wizard
// calibrates gravity there, three runs averaged and accepted by hapticd (Eq. 2).
TEST(CaptureWizardOnATripod, CalibratesGravityThreeTimesAndHapticdAcceptsTheAverage) {
  g_warnings.clear();
  test::Hapticd daemon({}, {"--rate", "5000"});
  ASSERT_TRUE(daemon.ready()) << daemon.log();
  Kiosk kiosk(daemon, "capture", QSize(1024, 600));
  ASSERT_NE(kiosk.window, nullptr);
  const DaemonLink& link = kiosk.link;
  const QStringList& messages = kiosk.messages;
  QQuickWindow* window = kiosk.window;
  Screen screen(window);
  ASSERT_TRUE(spin_until([&] { return link.connected(); })) << daemon.log();

  ASSERT_TRUE(spin_until([&] { return screen.tap("mountTripod") && screen.shows("calibrateGravity"); }))
      << "tripod tile: " << screen.shows("mountTripod") << ", mounting row: " << screen.shows("gravityState");
  // A revolution each way in 4 s rather than the thesis' 16 s: the runs take
  // 11 s each instead of 35 s in real time, and still qualify on the sim.
  ASSERT_TRUE(screen.item("captureWizard")->setProperty("gravitySeconds", 4.0));
  ASSERT_TRUE(screen.tap("calibrateGravity"));
  ASSERT_TRUE(spin_until([&] { return screen.text("gravityState").startsWith("Calibrating gravity: run 2"); }, 120000))
      << screen.text("gravityState").toStdString() << " / " << messages.join(" | ").toStdString();
  // Three runs of a revolution each way.
  ASSERT_TRUE(spin_until([&] { return screen.text("gravityState").startsWith("Gravity calibrated"); }, 300000))
      << screen.text("gravityState").toStdString() << " / " << messages.join(" | ").toStdString();
  screen.shoot("capture-1-tripod-1024x600");
  // hapticd holds the accepted average, three runs of it.
  control::Client c(daemon.socket());
  const nlohmann::json state = c.call("get_state");
  ASSERT_TRUE(state["calibration"]["accepted"].contains("gravity")) << state.dump();
  EXPECT_EQ(state["calibration"]["accepted"]["gravity"]["repetitions"], 3) << state.dump();
  // Each run as the wizard asked: 2 × (3 ramps of 0.5 s + 4 s) at 5 kHz.
  EXPECT_EQ(state["last_calibration"]["samples"], 2 * (3 * 2500 + 20000)) << state["last_calibration"].dump();
  EXPECT_TRUE(g_warnings.isEmpty()) << g_warnings.join("\n").toStdString();
}

INSTANTIATE_TEST_SUITE_P(AtPanelSizes, CaptureWizard, ::testing::Values(QSize(1024, 600), QSize(1280, 800)),
                         [](const auto& p) {
                           return std::to_string(p.param.width()) + "_" + std::to_string(p.param.height());
                         });

}  // namespace
}  // namespace knoblab::ui

int main(int argc, char** argv) {
  // Offscreen, the software renderer: no display needed, the same pixels anywhere.
  qputenv("QT_QPA_PLATFORM", "offscreen");
  qputenv("QT_QUICK_BACKEND", "software");
  qputenv("QT_IM_MODULE", "qtvirtualkeyboard");  // as knoblab-ui selects it
  qInstallMessageHandler(knoblab::ui::keep_warnings);
  QGuiApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
