// A study's rendering as hapticd's render model takes it, for both
// apparatus: hapticd writes the detents τ = A_pos·sin(θ/P_pos), so P_pos is
// 1/detents per revolution; without detents there is no detent torque.
#pragma once

#include "knoblab/study/protocol.hpp"

namespace knoblab::studyrun::detail {

struct RenderTerms {
  double M_acc, B_vel, A_pos, P_pos;
};

inline RenderTerms render_terms(const study::Rendering& r) {
  const bool detents = r.detents_per_rev > 0;
  return {r.M_acc, r.B_vel, detents ? r.A_pos : 0.0, detents ? 1.0 / r.detents_per_rev : 1.0};
}

}  // namespace knoblab::studyrun::detail
