// Poller against the in-process simulator over real TCP loopback: sample
// rate and exactly-once delivery, fault bits and their timing, commands,
// reconnects, bounded shutdown.
#include <gtest/gtest.h>

#include <modbus.h>
#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "knoblab/modbus/poller.hpp"
#include "knoblab/modbus/register_map.hpp"
#include "knoblab/modbus/sim_server.hpp"
#include "support.hpp"

namespace knoblab::modbus {
namespace {

using namespace test;

class PollerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SimConfig sc;
    sc.seed = 42;
    sim_ = std::make_unique<SimServer>(sc);
    std::string error;
    ASSERT_TRUE(sim_->start(&error)) << error;
  }

  void start_poller(PollerConfig c) {
    c.on_sample = [this](const BiometricSample& s) {
      std::lock_guard lock(mutex_);
      samples_.push_back(s);
      sched_param sp{};
      pthread_getschedparam(pthread_self(), &policy_, &sp);  // the poller thread's
      priority_ = sp.sched_priority;
    };
    poller_ = std::make_unique<Poller>(std::move(c));
    poller_->start();
  }
  void start_poller() { start_poller(local_config(sim_->port())); }

  // Both devices read, nothing wrong.
  void wait_healthy() {
    ASSERT_TRUE(wait_for([&] { return (poller_->status() & status::kProblemMask) == 0; }, 2s))
        << status::describe(poller_->status()) << " / " << poller_->stats().last_error;
  }

  std::vector<BiometricSample> samples() {
    std::lock_guard lock(mutex_);
    return samples_;
  }

  void TearDown() override {
    if (poller_) poller_->stop();
    sim_->stop();
  }

  std::unique_ptr<SimServer> sim_;
  std::unique_ptr<Poller> poller_;
  std::mutex mutex_;
  std::vector<BiometricSample> samples_;
  int policy_ = -1, priority_ = -1;  // of the thread that delivered the last sample
};

TEST_F(PollerTest, ItsThreadsRunRealtimeAtTheConfiguredPriority) {
  if (geteuid() != 0) GTEST_SKIP() << "SCHED_FIFO needs root (CAP_SYS_NICE)";
  PollerConfig c = local_config(sim_->port());
  c.priority = 40;
  start_poller(c);
  wait_healthy();
  ASSERT_TRUE(wait_for([&] { return !samples().empty(); }, 2s));
  EXPECT_TRUE(poller_->stats().realtime) << poller_->stats().last_error;
  std::lock_guard lock(mutex_);
  EXPECT_EQ(policy_, SCHED_FIFO);
  EXPECT_EQ(priority_, 40);
}

TEST_F(PollerTest, WithoutAPriorityItsThreadsRunOrdinary) {
  start_poller();
  wait_healthy();
  ASSERT_TRUE(wait_for([&] { return !samples().empty(); }, 2s));
  EXPECT_FALSE(poller_->stats().realtime);
  std::lock_guard lock(mutex_);
  EXPECT_EQ(policy_, SCHED_OTHER);
}

TEST_F(PollerTest, BiometricsArriveAt32HzExactlyOnce) {
  start_poller();
  wait_healthy();
  const auto t0 = Clock::now();
  std::uint32_t problems = 0;  // any problem bit seen while healthy
  while (Clock::now() - t0 < 2s) {
    problems |= poller_->status() & status::kProblemMask;
    std::this_thread::sleep_for(1ms);
  }
  const auto all = samples();
  const auto in_window = std::count_if(all.begin(), all.end(), [&](const BiometricSample& s) {
    return s.received >= t0 && s.received < t0 + 2s;
  });
  EXPECT_NEAR(static_cast<double>(in_window), 64.0, 3.0);
  EXPECT_EQ(problems, 0u) << status::describe(problems);

  ASSERT_GE(all.size(), 2u);
  std::set<std::uint32_t> seen;
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_TRUE(seen.insert(all[i].counter).second) << "duplicate " << all[i].counter;
    if (i > 0) {
      EXPECT_EQ(all[i].counter, all[i - 1].counter + 1);
      EXPECT_NEAR(all[i].box_time_ms - all[i - 1].box_time_ms, 31.25, 1.0);  // the box's 32 Hz clock
      EXPECT_GT(all[i].taken, all[i - 1].taken);
    }
    EXPECT_LE(all[i].taken, all[i].received);  // taken by the box before we read it
    EXPECT_GT(all[i].skin_conductance, 0.3e-6);  // a few µS, SI units
    EXPECT_LT(all[i].skin_conductance, 30e-6);
    EXPECT_LT(std::abs(all[i].emg_corrugator), 1e-3);  // µV-scale volts
  }
  const PollerStats st = poller_->stats();
  EXPECT_EQ(st.samples_missed, 0u);
  EXPECT_EQ(st.samples_delivered, all.size());
  EXPECT_GT(st.amp_reads, 150u);  // ~100 Hz
}

TEST_F(PollerTest, AmpFaultInjectedThroughControlRegistersSetsTheBitWithin100ms) {
  start_poller();
  wait_healthy();
  modbus_t* ctl = modbus_new_tcp("127.0.0.1", sim_->port());
  ASSERT_NE(ctl, nullptr);
  ASSERT_EQ(modbus_connect(ctl), 0);
  modbus_set_slave(ctl, kDefaultSimControlUnit);
  const auto t0 = Clock::now();
  ASSERT_EQ(modbus_write_register(ctl, simctl::kAmpFaultInject, amp::fault::kOverCurrent), 1);
  const auto took = wait_for([&] { return has(poller_->status(), status::kAmpFault); }, 500ms);
  ASSERT_TRUE(took);
  EXPECT_LE(std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t0).count(), 100);
  ASSERT_TRUE(poller_->amplifier());
  EXPECT_EQ(poller_->amplifier()->faults & amp::fault::kOverCurrent, amp::fault::kOverCurrent);
  EXPECT_FALSE(has(poller_->status(), status::kAmpCommsLost));  // a fault is not a lost link

  // The control block identifies itself and counts what it served.
  std::uint16_t in[simctl::kInputCount] = {};
  ASSERT_EQ(modbus_read_input_registers(ctl, 0, simctl::kInputCount, in), simctl::kInputCount);
  EXPECT_EQ(in[ident::kDeviceType], static_cast<std::uint16_t>(DeviceType::sim_control));
  EXPECT_GT(join_u32(in[simctl::kRequestsServed], in[simctl::kRequestsServed + 1]), 2u);
  EXPECT_GE(in[simctl::kClients], 3);  // amp, biometrics, us
  modbus_close(ctl);
  modbus_free(ctl);
}

TEST_F(PollerTest, CommandsReachTheAmplifierAndAFaultDisablesItUnexpectedly) {
  start_poller();
  wait_healthy();
  ASSERT_TRUE(poller_->set_current_limit(5.0));
  ASSERT_TRUE(poller_->enable());
  ASSERT_TRUE(wait_for([&] { return has(poller_->status(), status::kAmpEnabled); }, 500ms));
  ASSERT_TRUE(wait_for([&] { return std::abs(poller_->amplifier()->current_limit - 5.0) < 1e-9; }, 500ms));
  EXPECT_NEAR(poller_->amplifier()->bus_voltage, 48.0, 1.0);
  EXPECT_GT(poller_->amplifier()->temperature, 20.0);
  EXPECT_FALSE(poller_->set_current_limit(25.0));  // beyond the 20 A peak: refused here
  EXPECT_FALSE(poller_->set_current_limit(-1.0));

  sim_->set_amp_fault(amp::fault::kOverTemperature);
  ASSERT_TRUE(wait_for([&] {
    return has(poller_->status(), status::kAmpFault | status::kAmpDisabledUnexpectedly);
  }, 500ms)) << status::describe(poller_->status());
  EXPECT_FALSE(has(poller_->status(), status::kAmpEnabled));

  // Cause gone + reset: fault clears, but the drive stays off until re-enabled.
  sim_->set_amp_fault(0);
  ASSERT_TRUE(poller_->clear_faults());
  ASSERT_TRUE(wait_for([&] { return !has(poller_->status(), status::kAmpFault); }, 500ms));
  EXPECT_TRUE(has(poller_->status(), status::kAmpDisabledUnexpectedly));
  ASSERT_TRUE(poller_->enable());
  ASSERT_TRUE(wait_for([&] {
    const auto w = poller_->status();
    return has(w, status::kAmpEnabled) && !has(w, status::kAmpDisabledUnexpectedly);
  }, 500ms));
  ASSERT_TRUE(poller_->disable());
  ASSERT_TRUE(wait_for([&] { return !has(poller_->status(), status::kAmpEnabled); }, 500ms));
  EXPECT_EQ(poller_->status() & status::kProblemMask, 0u);
  EXPECT_EQ(poller_->stats().commands_failed, 0u);
  EXPECT_EQ(poller_->stats().commands_rejected, 2u);
}

TEST_F(PollerTest, DisconnectSetsCommsLostWithinTheTimeoutThenRecovers) {
  start_poller();
  wait_healthy();
  const auto connects_before = poller_->stats().connects;
  const auto t0 = Clock::now();
  sim_->drop_connections(400ms);  // drop everyone, refuse new clients for 400 ms
  ASSERT_TRUE(wait_for([&] { return has(poller_->status(), status::kAmpCommsLost); }, 1s));
  const auto lost_after = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t0);
  EXPECT_LE(lost_after.count(), 50 + 30) << "comms_timeout is 50 ms";
  ASSERT_TRUE(wait_for([&] { return has(poller_->status(), status::kBiometricsLost); }, 1s));

  // Recovers by itself once the server accepts again (backoff ≤ 200 ms here).
  ASSERT_TRUE(wait_for([&] { return (poller_->status() & status::kProblemMask) == 0; }, 3s))
      << status::describe(poller_->status());
  EXPECT_GE(Clock::now() - t0, 400ms);
  EXPECT_GE(poller_->stats().connects, connects_before + 2);

  // Samples resume in order; the ring backfills what it still holds.
  const auto before = samples().size();
  ASSERT_TRUE(wait_for([&] { return samples().size() >= before + 4; }, 1s));
  const auto all = samples();
  for (std::size_t i = 1; i < all.size(); ++i) EXPECT_GT(all[i].counter, all[i - 1].counter);
}

TEST_F(PollerTest, ExceptionRepliesAreCountedAndFlagged) {
  start_poller();
  wait_healthy();
  sim_->set_exception(kDefaultAmplifierUnit, MODBUS_EXCEPTION_GATEWAY_TARGET);
  sim_->set_exception(kDefaultBiometricsUnit, MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE);
  ASSERT_TRUE(wait_for([&] {
    return has(poller_->status(), status::kAmpException | status::kBiometricsException);
  }, 200ms));
  // No good read either: after the timeouts the links count as lost too.
  ASSERT_TRUE(wait_for([&] {
    return has(poller_->status(), status::kAmpCommsLost | status::kBiometricsLost);
  }, 300ms));
  const PollerStats st = poller_->stats();
  EXPECT_GT(st.amp_exceptions, 2u);
  EXPECT_GT(st.bio_exceptions, 2u);
  EXPECT_NE(st.last_error.find("unit"), std::string::npos) << st.last_error;
  // Exceptions are answers: no reconnects.
  EXPECT_EQ(st.connects, 2u);

  sim_->set_exception(kDefaultAmplifierUnit, 0);
  sim_->set_exception(kDefaultBiometricsUnit, 0);
  wait_healthy();
}

TEST_F(PollerTest, FrozenBiometricsSetTheStaleBitNotTheLostBit) {
  start_poller();
  wait_healthy();
  const auto t0 = Clock::now();
  sim_->set_freeze(simctl::kFreezeBiometrics);
  ASSERT_TRUE(wait_for([&] { return has(poller_->status(), status::kBiometricsStale); }, 1s));
  const auto stale_after = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t0);
  // > 3 periods (93.75 ms) after the last new sample, seen up to ~40 ms before the freeze.
  EXPECT_GE(stale_after.count(), 40);
  EXPECT_LE(stale_after.count(), 160);
  std::this_thread::sleep_for(100ms);
  EXPECT_FALSE(has(poller_->status(), status::kBiometricsLost));  // reads still succeed
  EXPECT_FALSE(has(poller_->status(), status::kAmpCommsLost));

  const auto before = samples().size();
  sim_->set_freeze(0);
  ASSERT_TRUE(wait_for([&] { return !has(poller_->status(), status::kBiometricsStale); }, 500ms));
  ASSERT_TRUE(wait_for([&] { return samples().size() > before; }, 500ms));
  const auto all = samples();
  for (std::size_t i = 1; i < all.size(); ++i) EXPECT_EQ(all[i].counter, all[i - 1].counter + 1);
}

TEST_F(PollerTest, FrozenAmplifierHeartbeatCountsAsCommsLost) {
  start_poller();
  wait_healthy();
  sim_->set_freeze(simctl::kFreezeAmplifier);
  ASSERT_TRUE(wait_for([&] { return has(poller_->status(), status::kAmpCommsLost); }, 300ms));
  EXPECT_EQ(poller_->stats().amp_errors, 0u);  // every read succeeded; the drive was still
  sim_->set_freeze(0);
  wait_healthy();
}

// Figures for a stalled box on a loaded 2-core machine: the 200 ms amp
// watchdog trips only if the amplifier thread itself starves that long,
// while a biometrics request left waiting 500..800 ms would trip it every
// time if amplifier reads had to wait behind it.
PollerConfig stall_tolerant_config(std::uint16_t port) {
  PollerConfig c = local_config(port);
  c.comms_timeout = 200ms;
  c.biometrics.response_timeout = 800ms;
  c.biometrics_timeout = 2000ms;
  return c;
}

TEST_F(PollerTest, ASlowBiometricsBoxNeverDelaysAmplifierReads) {
  const PollerConfig c = stall_tolerant_config(sim_->port());
  start_poller(c);
  wait_healthy();
  constexpr auto kReplyDelay = 500ms;  // each box answer, inside its 800 ms response timeout
  sim_->set_reply_delay(kDefaultBiometricsUnit, kReplyDelay);
  const PollerStats before = poller_->stats();
  std::uint32_t tripped = 0;
  const auto t0 = Clock::now();
  while (Clock::now() - t0 < 2s) {
    tripped |= poller_->status() & status::kAmpTripMask;
    std::this_thread::sleep_for(1ms);
  }
  const PollerStats after = poller_->stats();
  EXPECT_EQ(tripped, 0u) << status::describe(tripped);
  // 2 s at 100 Hz is 200 reads; a quarter of that survives any scheduler,
  // while waiting behind the box would allow only about one per reply.
  EXPECT_GT(after.amp_reads - before.amp_reads, 2s / c.amplifier_period / 4);
  // The box was polled all along, slowly: not a vacuous pass.
  EXPECT_GE(after.bio_reads - before.bio_reads, 1u);
  EXPECT_LE(after.bio_reads - before.bio_reads, 2s / kReplyDelay + 2);

  sim_->set_reply_delay(kDefaultBiometricsUnit, 0ms);
  wait_healthy();
}

TEST_F(PollerTest, AHungBiometricsBoxNeverDelaysAmplifierReadsOrCommands) {
  const PollerConfig c = stall_tolerant_config(sim_->port());
  start_poller(c);
  wait_healthy();
  sim_->set_mute(simctl::kMuteBiometrics);  // connected, never answers
  ASSERT_TRUE(wait_for([&] { return has(poller_->status(), status::kBiometricsLost); }, 5s));
  const PollerStats before = poller_->stats();
  std::uint32_t tripped = 0;
  auto watch = [&](std::chrono::milliseconds d) {
    const auto t0 = Clock::now();
    while (Clock::now() - t0 < d) {
      tripped |= poller_->status() & status::kAmpTripMask;
      std::this_thread::sleep_for(1ms);
    }
  };
  ASSERT_TRUE(poller_->enable());
  ASSERT_TRUE(wait_for([&] { return has(poller_->status(), status::kAmpEnabled); }, 2s));
  watch(1s);
  ASSERT_TRUE(poller_->disable());
  ASSERT_TRUE(wait_for([&] { return !has(poller_->status(), status::kAmpEnabled); }, 2s));
  watch(1s);
  const PollerStats after = poller_->stats();
  EXPECT_EQ(tripped, 0u) << status::describe(tripped);
  EXPECT_GT(after.amp_reads - before.amp_reads, 2s / c.amplifier_period / 4);
  EXPECT_EQ(after.commands_done - before.commands_done, 2u);
  EXPECT_EQ(after.commands_failed, 0u);
  EXPECT_GT(after.bio_errors, before.bio_errors);  // the box was tried all along
  EXPECT_TRUE(has(poller_->status(), status::kBiometricsLost));

  sim_->set_mute(0);
  wait_healthy();
}

TEST_F(PollerTest, StopIsBoundedWhenTheServerHangs) {
  PollerConfig c = local_config(sim_->port());
  c.amplifier.response_timeout = 50ms;
  c.biometrics.response_timeout = 50ms;
  c.comms_timeout = 100ms;  // above period + response timeout: one lost answer is no lost link
  start_poller(c);
  wait_healthy();
  sim_->set_mute(simctl::kMuteAmplifier | simctl::kMuteBiometrics);
  ASSERT_TRUE(wait_for([&] { return has(poller_->status(), status::kAmpCommsLost); }, 500ms));
  const auto t0 = Clock::now();
  poller_->stop();
  EXPECT_LT(Clock::now() - t0, 200ms);
  EXPECT_TRUE(has(poller_->status(), status::kAmpCommsLost | status::kBiometricsLost));
  EXPECT_FALSE(has(poller_->status(), status::kRunning));
  EXPECT_FALSE(poller_->enable());  // not running: refused, not queued
}

TEST_F(PollerTest, AThrowingConsumerDoesNotStopPolling) {
  PollerConfig c = local_config(sim_->port());
  std::atomic<int> calls{0};
  c.on_sample = [&](const BiometricSample&) {
    ++calls;
    throw std::runtime_error("disk full");
  };
  poller_ = std::make_unique<Poller>(std::move(c));
  poller_->start();
  ASSERT_TRUE(wait_for([&] { return calls.load() >= 3; }, 1s));
  EXPECT_EQ(poller_->status() & status::kProblemMask, 0u);
  EXPECT_NE(poller_->stats().last_error.find("disk full"), std::string::npos);
}

TEST_F(PollerTest, SwappedUnitIdsAreAnAmplifierMismatchThatCutsTorque) {
  PollerConfig c = local_config(sim_->port());
  c.amplifier.unit_id = kDefaultBiometricsUnit;
  c.biometrics.unit_id = kDefaultAmplifierUnit;
  start_poller(c);
  ASSERT_TRUE(wait_for([&] { return has(poller_->status(), status::kAmpMismatch); }, 500ms))
      << status::describe(poller_->status());
  std::this_thread::sleep_for(100ms);
  EXPECT_TRUE(has(poller_->status(), status::kAmpCommsLost | status::kBiometricsLost));
  EXPECT_NE(poller_->status() & status::kAmpTripMask & status::kAmpMismatch, 0u);
  // The amp has too few registers for the box's read: an exception, not data.
  EXPECT_TRUE(has(poller_->status(), status::kBiometricsException));
  EXPECT_TRUE(samples().empty());
  EXPECT_GT(poller_->stats().mismatches, 0u);
}

TEST_F(PollerTest, ABiometricsMapMismatchNeverCutsTorque) {
  sim_->set_map_version(kDefaultBiometricsUnit, kMapVersion + 1);  // a box with other firmware
  start_poller();
  ASSERT_TRUE(wait_for([&] {
    const auto w = poller_->status();
    return has(w, status::kBiometricsMismatch) && (w & status::kAmpTripMask) == 0;
  }, 2s)) << status::describe(poller_->status());
  std::uint32_t tripped = 0, seen = ~0u;
  const auto t0 = Clock::now();
  while (Clock::now() - t0 < 500ms) {
    const auto w = poller_->status();
    tripped |= w & status::kAmpTripMask;
    seen &= w;  // bits held throughout
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_EQ(tripped, 0u) << status::describe(tripped);
  EXPECT_TRUE(has(seen, status::kBiometricsMismatch)) << status::describe(seen);
  EXPECT_TRUE(samples().empty());  // nothing from the wrong device is used
  const PollerStats st = poller_->stats();
  EXPECT_GT(st.amp_reads, 0u);
  EXPECT_NE(st.last_error.find("biometrics"), std::string::npos) << st.last_error;
}

}  // namespace
}  // namespace knoblab::modbus
