// The simulator's timing faults: a slow unit answers late and a hung one not
// at all, while the other units on the same server keep answering at once.
// The poller tests rely on both to stall one device but not the other.
#include <gtest/gtest.h>

#include <modbus.h>

#include <atomic>
#include <cerrno>
#include <thread>

#include "knoblab/modbus/fault_spec.hpp"
#include "knoblab/modbus/register_map.hpp"
#include "knoblab/modbus/sim_server.hpp"
#include "support.hpp"

namespace knoblab::modbus {
namespace {

using namespace test;

// A libmodbus TCP client for one unit of a local simulator.
class Client {
 public:
  Client(std::uint16_t port, int unit, std::chrono::milliseconds timeout) {
    ctx_ = modbus_new_tcp("127.0.0.1", port);
    if (ctx_ == nullptr) return;
    const auto ms = static_cast<std::uint32_t>(timeout.count());
    modbus_set_response_timeout(ctx_, ms / 1000, (ms % 1000) * 1000);
    modbus_set_slave(ctx_, unit);
    connected_ = modbus_connect(ctx_) == 0;
  }
  ~Client() {
    if (ctx_ == nullptr) return;
    modbus_close(ctx_);
    modbus_free(ctx_);
  }
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  bool connected() const { return connected_; }
  // Reads the identity block; the device type, or -errno.
  int device_type() {
    std::uint16_t id[2] = {};
    if (modbus_read_input_registers(ctx_, 0, 2, id) != 2) return -errno;
    return id[ident::kDeviceType];
  }

 private:
  modbus_t* ctx_ = nullptr;
  bool connected_ = false;
};

constexpr int kAmp = static_cast<int>(DeviceType::amplifier);
constexpr int kBio = static_cast<int>(DeviceType::biometrics);

TEST(SimTimingFaults, ASlowUnitHoldsOnlyItsOwnReplies) {
  SimServer sim({});
  ASSERT_TRUE(sim.start());
  constexpr auto kDelay = 1500ms;  // far longer than a few loopback reads, even on a loaded machine
  sim.set_reply_delay(kDefaultBiometricsUnit, kDelay);

  std::atomic<bool> bio_done{false};
  int bio_answer = 0;
  Clock::duration bio_took{};
  std::thread slow([&] {
    Client bio(sim.port(), kDefaultBiometricsUnit, 10s);
    const auto t0 = Clock::now();
    bio_answer = bio.connected() ? bio.device_type() : -1;
    bio_took = Clock::now() - t0;
    bio_done = true;
  });
  // Meanwhile the amplifier, on its own connection, answers every time.
  Client amp(sim.port(), kDefaultAmplifierUnit, 1s);
  ASSERT_TRUE(amp.connected());
  int amp_answers = 0;
  for (int i = 0; i < 5; ++i) amp_answers += amp.device_type() == kAmp ? 1 : 0;
  const bool bio_still_waiting = !bio_done.load();
  slow.join();

  EXPECT_EQ(amp_answers, 5);
  EXPECT_TRUE(bio_still_waiting);
  EXPECT_EQ(bio_answer, kBio);  // late, but a correct answer
  EXPECT_GE(bio_took, kDelay);

  sim.set_reply_delay(kDefaultBiometricsUnit, 0ms);
  Client bio(sim.port(), kDefaultBiometricsUnit, 1s);
  EXPECT_EQ(bio.device_type(), kBio);
  sim.stop();
}

TEST(SimTimingFaults, ScheduledSlowAndHangFaultsTakeEffect) {
  SimConfig config;
  for (const char* spec : {"slow=300:amp", "hang-after=0:bio"}) {
    std::string error;
    const auto fault = parse_fault(spec, &error);
    ASSERT_TRUE(fault) << error;
    config.faults.push_back(*fault);
  }
  SimServer sim(config);
  ASSERT_TRUE(sim.start());  // faults at 0 s apply before the first request is served

  Client amp(sim.port(), kDefaultAmplifierUnit, 5s);
  const auto t0 = Clock::now();
  EXPECT_EQ(amp.device_type(), kAmp);
  EXPECT_GE(Clock::now() - t0, 300ms);

  Client bio(sim.port(), kDefaultBiometricsUnit, 300ms);
  ASSERT_TRUE(bio.connected());  // a hung device still accepts the connection
  EXPECT_EQ(bio.device_type(), -ETIMEDOUT);
  sim.stop();
}

}  // namespace
}  // namespace knoblab::modbus
