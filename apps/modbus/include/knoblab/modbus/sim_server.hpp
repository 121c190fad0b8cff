// The Modbus TCP simulator of the servo amplifier and the biometrics box,
// as a library class so tests can run it in-process (knoblab-modbus-sim
// wraps it for the command line). One thread, one select() loop, several
// clients; register maps in register_map.hpp, fault injection through the
// control unit's registers or the methods below (same effect).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "knoblab/modbus/fault_spec.hpp"
#include "knoblab/modbus/register_map.hpp"

namespace knoblab::modbus {

struct SimConfig {
  std::string bind = "127.0.0.1";  // IPv4 address; 0.0.0.0 for every interface
  std::uint16_t port = 0;          // 0: an ephemeral port (see SimServer::port())
  std::uint64_t seed = 1;
  int amplifier_unit = kDefaultAmplifierUnit;
  int biometrics_unit = kDefaultBiometricsUnit;
  int control_unit = kDefaultSimControlUnit;
  std::vector<FaultAction> faults;        // scheduled from start()
  std::chrono::milliseconds duration{0};  // > 0: the server stops itself after this
  // Limits that keep hostile clients from starving good ones.
  int max_clients = 32;
  std::chrono::milliseconds idle_timeout{10'000};       // no complete request for this long
  std::chrono::milliseconds partial_frame_timeout{1'000};// a frame started, never finished
};

struct SimCounters {
  std::uint64_t requests = 0;     // frames answered or deliberately ignored
  std::uint64_t bad_frames = 0;   // not Modbus TCP; the client was dropped
  std::uint64_t exceptions = 0;   // exception replies sent (illegal or injected)
  std::uint64_t dropped = 0;      // clients dropped (bad frames, timeouts, faults)
  int clients = 0;                // connected now
  std::uint32_t sample_counter = 0;  // the biometrics box's counter
};

class SimDevices;

class SimServer {
 public:
  explicit SimServer(SimConfig config);
  ~SimServer();
  SimServer(const SimServer&) = delete;
  SimServer& operator=(const SimServer&) = delete;

  // Binds and starts the thread. False (and *error) if it cannot bind.
  bool start(std::string* error = nullptr);
  void stop();  // joins; the loop wakes every few ms
  bool running() const { return running_.load(); }
  std::uint16_t port() const { return port_; }  // the bound port, after start()

  // Fault injection, thread-safe; each is a write to the control registers.
  void set_exception(int unit, int code);  // code 0: answer normally again
  void set_freeze(std::uint16_t bits);     // simctl::kFreeze* bits; 0: live again
  void set_amp_fault(std::uint16_t bits);  // amp::fault bits whose cause is present; 0: gone
  void set_mute(std::uint16_t bits);       // simctl::kMute* bits
  // Hold each reply of unit back this long (0..65535 ms; 0: prompt again).
  // Only that unit's connections wait: the others are served meanwhile.
  void set_reply_delay(int unit, std::chrono::milliseconds delay);
  // The map version unit reports (another firmware); 0: the real one again.
  void set_map_version(int unit, std::uint16_t version);
  void drop_connections(std::chrono::milliseconds refuse_for);
  void stimulus();

  SimCounters counters() const;

 private:
  struct Client;
  void run();
  void serve_client(Client& c, std::chrono::steady_clock::time_point now);
  void answer_frames(Client& c, std::chrono::steady_clock::time_point now);
  void answer(Client& c, const std::uint8_t* frame, std::size_t length,
              std::chrono::steady_clock::time_point now);
  void accept_clients(std::chrono::steady_clock::time_point now);
  void apply_schedule(std::chrono::steady_clock::time_point now);
  void drop_all();
  void write_control(std::uint16_t reg, std::uint16_t value);

  SimConfig config_;
  std::unique_ptr<SimDevices> devices_;
  void* ctx_ = nullptr;  // modbus_t*, used only to build replies
  int listen_fd_ = -1;
  std::uint16_t port_ = 0;
  std::vector<std::unique_ptr<Client>> clients_;
  std::vector<bool> schedule_done_;
  std::chrono::steady_clock::time_point start_{};
  std::chrono::steady_clock::time_point refuse_until_{};
  SimCounters counters_;

  mutable std::mutex mutex_;  // devices_, counters_, between the loop and the API
  std::atomic<bool> stop_{false};
  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace knoblab::modbus
