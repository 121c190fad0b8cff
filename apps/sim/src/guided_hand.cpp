#include "knoblab/sim/guided_hand.hpp"

#include <algorithm>
#include <cmath>

namespace knoblab::sim {

bool valid(const HandCommand& c) {
  return std::isfinite(c.target_rad) && std::abs(c.target_rad) <= kMaxHandAngle && c.duration_s >= 0 &&
         c.duration_s <= kMaxReach && c.stiffness >= 0 && c.stiffness <= kMaxHandStiffness && c.damping >= 0 &&
         c.damping <= kMaxHandDamping;  // NaN fails every comparison
}

void HandChannel::send(const HandCommand& c) noexcept {
  const std::uint64_t s = seq_.load(std::memory_order_relaxed);
  seq_.store(s + 1, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);
  target_.store(c.target_rad, std::memory_order_relaxed);
  duration_.store(c.duration_s, std::memory_order_relaxed);
  stiffness_.store(c.stiffness, std::memory_order_relaxed);
  damping_.store(c.damping, std::memory_order_relaxed);
  seq_.store(s + 2, std::memory_order_release);
}

bool HandChannel::receive(std::uint64_t& last_seen, HandCommand& out) const noexcept {
  const std::uint64_t before = seq_.load(std::memory_order_acquire);
  if (before == last_seen || (before & 1u) != 0) return false;
  HandCommand c{target_.load(std::memory_order_relaxed), duration_.load(std::memory_order_relaxed),
                stiffness_.load(std::memory_order_relaxed), damping_.load(std::memory_order_relaxed)};
  std::atomic_thread_fence(std::memory_order_acquire);
  if (seq_.load(std::memory_order_relaxed) != before) return false;
  last_seen = before;
  out = c;
  return true;
}

ReachPoint minimum_jerk(double from, double to, double duration_s, double elapsed_s) {
  if (!(duration_s > 0) || elapsed_s >= duration_s) return {to, 0};
  const double s = std::max(0.0, elapsed_s) / duration_s;
  const double s2 = s * s;
  const double shape = s2 * s * (10 - 15 * s + 6 * s2);
  const double rate = 30 * s2 * (1 - 2 * s + s2) / duration_s;  // d(shape)/dt
  return {from + (to - from) * shape, (to - from) * rate};
}

namespace {

class GuidedHand final : public KnobEffect {
 public:
  GuidedHand(HandChannel& channel, std::shared_ptr<void> keep) : channel_(channel), keep_(std::move(keep)) {}

  double torque(const KnobMotion& knob, double t) const override {
    if (grip_.stiffness == 0 && grip_.damping == 0) return 0;
    const ReachPoint h = minimum_jerk(from_, grip_.target_rad, grip_.duration_s, t - start_);
    return -(grip_.stiffness * (h.theta - knob.theta) + grip_.damping * (h.omega - knob.omega));
  }

  void advance(const KnobMotion& knob, double t, double) override {
    HandCommand c;
    if (!channel_.receive(seen_, c) || !valid(c)) return;
    // A hand that takes hold takes hold where the knob is; one already
    // holding starts its next reach from where it has got to.
    const bool holding = grip_.stiffness > 0 || grip_.damping > 0;
    from_ = holding ? minimum_jerk(from_, grip_.target_rad, grip_.duration_s, t - start_).theta : knob.theta;
    start_ = t;
    grip_ = c;
  }

  void reset() override {
    grip_ = {};
    from_ = start_ = 0;
  }

 private:
  HandChannel& channel_;
  std::shared_ptr<void> keep_;
  std::uint64_t seen_ = 0;
  HandCommand grip_{};
  double from_ = 0;
  double start_ = 0;
};

}  // namespace

std::unique_ptr<KnobEffect> make_guided_hand(HandChannel& channel, std::shared_ptr<void> keep) {
  return std::make_unique<GuidedHand>(channel, std::move(keep));
}

}  // namespace knoblab::sim
