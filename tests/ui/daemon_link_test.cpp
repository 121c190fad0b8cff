// The UI's link to the real hapticd (sim backend): it comes up by itself
// when the daemon starts, says when it is lost, comes back when the daemon
// restarts, supervises unless another client does, and reports a refused
// request. Deadlines only bound a wait for an outcome.
#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QElapsedTimer>

#include <functional>
#include <memory>

#include "daemon_link.hpp"
#include "event_loop.hpp"
#include "hapticd_process.hpp"
#include "library_reader.hpp"

namespace knoblab::ui {
namespace {

using test::Hapticd;
using test::ScratchDir;

bool spin_until(const std::function<bool()>& done, int ms = 20000) { return test_loop::spin_until(done, ms); }

LinkWorker::Options at(const std::string& socket) {
  LinkWorker::Options o;
  o.socket = QString::fromStdString(socket);
  o.reconnect_ms = 200;
  return o;
}

std::unique_ptr<Hapticd> hapticd_at(const std::string& socket) {
  return std::make_unique<Hapticd>(std::string{}, std::vector<std::string>{"--socket", socket});
}

TEST(DaemonLink, ComesUpByItselfWhenHapticdStartsAfterTheUi) {
  ScratchDir dir;
  const std::string socket = (dir / "h.sock").string();
  DaemonLink link(at(socket));
  ASSERT_TRUE(spin_until([&] { return !link.problem().isEmpty(); })) << "no reason given for the missing daemon";
  EXPECT_FALSE(link.connected());
  const auto daemon = hapticd_at(socket);
  ASSERT_TRUE(spin_until([&] { return link.connected() && link.mode() == "idle"; })) << daemon->log();
  EXPECT_TRUE(link.problem().isEmpty());
  // The loop turns: its rate is measured from the cycle counter.
  ASSERT_TRUE(spin_until([&] { return link.measuredRateHz() > 0; }));
  EXPECT_TRUE(link.supervising());
}

TEST(DaemonLink, ALostDaemonIsSaidAndTheLinkReturnsWhenItRestarts) {
  ScratchDir dir;
  const std::string socket = (dir / "h.sock").string();
  DaemonLink link(at(socket));
  QStringList messages;
  QObject::connect(&link, &DaemonLink::message, [&](const QString& text, const QString&) { messages << text; });
  auto daemon = hapticd_at(socket);
  ASSERT_TRUE(spin_until([&] { return link.connected(); })) << daemon->log();
  daemon.reset();  // SIGTERM
  ASSERT_TRUE(spin_until([&] { return !link.connected(); }));
  EXPECT_FALSE(link.problem().isEmpty());
  EXPECT_EQ(link.measuredRateHz(), 0.0);
  ASSERT_FALSE(messages.isEmpty());
  EXPECT_TRUE(messages.last().startsWith("lost hapticd")) << messages.last().toStdString();
  daemon = hapticd_at(socket);
  ASSERT_TRUE(spin_until([&] { return link.connected(); })) << daemon->log();
  EXPECT_TRUE(spin_until([&] { return messages.last() == "reconnected to hapticd"; }))
      << messages.join(" | ").toStdString();
}

TEST(DaemonLink, WithAnotherSupervisorThereTheLinkOnlyWatches) {
  ScratchDir dir;
  const std::string socket = (dir / "h.sock").string();
  const auto daemon = hapticd_at(socket);
  DaemonLink first(at(socket));
  ASSERT_TRUE(spin_until([&] { return first.connected() && first.supervising(); })) << daemon->log();
  DaemonLink second(at(socket));
  ASSERT_TRUE(spin_until([&] { return second.connected() && !second.state().isEmpty(); })) << daemon->log();
  EXPECT_FALSE(second.supervising());
  EXPECT_TRUE(first.supervising());
}

TEST(DaemonLink, ARefusedRequestComesBackAsAnErrorMessage) {
  ScratchDir dir;
  const std::string socket = (dir / "h.sock").string();
  const auto daemon = hapticd_at(socket);
  DaemonLink link(at(socket));
  ASSERT_TRUE(spin_until([&] { return link.connected(); })) << daemon->log();
  QString level, text;
  QObject::connect(&link, &DaemonLink::message, [&](const QString& t, const QString& l) { text = t, level = l; });
  bool replied = false, ok = true;
  QObject::connect(&link, &DaemonLink::replied,
                   [&](int, const QString&, bool good, const QVariantMap&, const QString&) { replied = true, ok = good; });
  link.request("set_mode", {{"mode", "warp"}});
  ASSERT_TRUE(spin_until([&] { return replied; }));
  EXPECT_FALSE(ok);
  EXPECT_EQ(level, "error");
  EXPECT_TRUE(text.startsWith("set_mode: ")) << text.toStdString();
  EXPECT_TRUE(link.connected()) << "a refused request is not a lost link";
}

TEST(DaemonLink, ACaptureIsStoredUnderItsMountingGripperAndNotes) {
  ScratchDir dir;
  const std::string socket = (dir / "h.sock").string();
  const auto daemon = hapticd_at(socket);
  DaemonLink link(at(socket));
  ASSERT_TRUE(spin_until([&] { return link.connected(); })) << daemon->log();
  qint64 capture = 0;
  QObject::connect(&link, &DaemonLink::event, [&](const QString& name, const QVariantMap& data) {
    if (name == "capture_finished") capture = data.value("capture_id").toLongLong();
  });
  bool refused = false;
  QObject::connect(&link, &DaemonLink::replied,
                   [&](int, const QString& cmd, bool ok, const QVariantMap&, const QString&) {
                     if (cmd == "start_capture" && !ok) refused = true;
                   });
  // A mounting that is neither is refused by the protocol, before anything starts.
  link.request("start_capture", {{"swept_sine", QVariantMap{{"a", 0}, {"b", 1.5}, {"c", 0.5}, {"d", 3}}},
                                 {"seconds", 0.3}, {"knob", "dash-knob"}, {"mounting", "ceiling"}});
  ASSERT_TRUE(spin_until([&] { return refused; }));
  link.request("start_capture", {{"swept_sine", QVariantMap{{"a", 0}, {"b", 1.5}, {"c", 0.5}, {"d", 3}}},
                                 {"seconds", 0.3},
                                 {"knob", "dash-knob"},
                                 {"mounting", "tripod"},
                                 {"gripper", "silicone cup"},
                                 {"notes", "car B, left stalk"}});
  ASSERT_TRUE(spin_until([&] { return capture > 0; })) << daemon->log();
  const auto entries = read_library(daemon->db());
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].capture_id, capture);
  EXPECT_EQ(entries[0].knob, "dash-knob");
  EXPECT_EQ(entries[0].mounting, "tripod");
  const nlohmann::json j = entry_json(entries[0]);
  EXPECT_EQ(j["gripper"], "silicone cup");
  EXPECT_EQ(j["notes"], "car B, left stalk");
}

}  // namespace
}  // namespace knoblab::ui
