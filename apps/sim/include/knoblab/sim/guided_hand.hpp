// A simulated hand that a simulated participant steers: the hand holds the
// knob through a compliant grip (as sim/hand.hpp) and moves it along
// minimum-jerk reaches, each asked for with a HandCommand. The rendered
// model pushes back, so friction lags the reach and inertia carries the knob
// past its end, as with a person's hand.
//
// The participant runs in another thread or process than the plant, so the
// commands cross a HandChannel: a seqlock of atomics, one writer, one reader,
// no allocation, lock or wait on either side. The plant picks up a new command
// in its next step and starts the reach from where the hand is then.
//   θ_h(t) = θ_from + (θ_to − θ_from)·(10s³ − 15s⁴ + 6s⁵),  s = (t − t₀)/T
//   hand torque = stiffness·(θ_h − θ) + damping·(θ̇_h − θ̇)
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

#include "knoblab/sim/effects.hpp"

namespace knoblab::sim {

struct HandCommand {
  double target_rad = 0;   // where the reach ends
  double duration_s = 0;   // its length; 0 jumps there (use only to let go or to hold)
  double stiffness = 0;    // grip, N·m/rad; 0: the hand is off the knob
  double damping = 0;      // grip, N·m·s/rad
  bool operator==(const HandCommand&) const = default;
};

// The grip's bounds: a command outside them, or not finite, is ignored by
// the plant (a hostile or broken writer cannot make the simulation blow up).
inline constexpr double kMaxHandStiffness = 100.0;  // N·m/rad
inline constexpr double kMaxHandDamping = 10.0;     // N·m·s/rad
inline constexpr double kMaxHandAngle = 1000.0;     // rad
inline constexpr double kMaxReach = 60.0;           // s
bool valid(const HandCommand& command);

// Standard layout and lock-free, so it can live in shared memory
// (hal::SharedHandChannel maps one by name for the daemon's sim backend).
class HandChannel {
 public:
  void send(const HandCommand& command) noexcept;
  // A command newer than `last_seen` (updated), or false when there is none
  // or the writer is midway through one (it is picked up next time).
  bool receive(std::uint64_t& last_seen, HandCommand& out) const noexcept;
  std::uint64_t sequence() const noexcept { return seq_.load(std::memory_order_acquire); }

 private:
  std::atomic<std::uint64_t> seq_{0};  // odd while a command is written
  std::atomic<double> target_{0}, duration_{0}, stiffness_{0}, damping_{0};
};
static_assert(std::atomic<std::uint64_t>::is_always_lock_free && std::atomic<double>::is_always_lock_free);

// The hand as a plant effect. `keep` is whatever owns the channel's memory
// (a shared-memory mapping); the effect holds it as long as it lives.
std::unique_ptr<KnobEffect> make_guided_hand(HandChannel& channel, std::shared_ptr<void> keep = {});

// The reach's position and velocity at s = (t − t₀)/T, for the participant's
// own planning as for the plant.
struct ReachPoint {
  double theta = 0;
  double omega = 0;
};
ReachPoint minimum_jerk(double from, double to, double duration_s, double elapsed_s);

}  // namespace knoblab::sim
