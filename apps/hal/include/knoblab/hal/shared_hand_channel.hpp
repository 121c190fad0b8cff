// The simulated hand's command channel (sim/guided_hand.hpp) in POSIX shared
// memory, by name, so that a simulated participant in another process
// (`knoblab study simulate`) can steer the hand on hapticd's sim backend.
// Either side may come first: both open the object, creating it if it is not
// there yet, and a restarted daemon finds the participant's channel as it was.
#pragma once

#include <memory>
#include <string>

#include "knoblab/sim/guided_hand.hpp"

namespace knoblab::hal {

class SharedHandChannel {
 public:
  // Throws std::runtime_error naming the object and the reason. The name is
  // '/' and a name without '/', as shm_open wants (e.g. "/knoblab-sim-hand").
  explicit SharedHandChannel(const std::string& name);

  sim::HandChannel& channel() const { return *channel_; }
  // Keeps the mapping alive for as long as whoever holds it (the plant's hand).
  std::shared_ptr<void> mapping() const { return mapping_; }

 private:
  std::shared_ptr<void> mapping_;
  sim::HandChannel* channel_ = nullptr;
};

}  // namespace knoblab::hal
