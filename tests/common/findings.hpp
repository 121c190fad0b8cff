// Reading a discrepancy result in tests: a finding by its effect, and a
// finding's parameter by name.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::test {

// The finding of effect `id`, or nullptr.
inline const discovery::Finding* finding(const discovery::DiscrepancyResult& r, discovery::EffectId id) {
  for (const discovery::Finding& f : r.findings)
    if (f.effect == id) return &f;
  return nullptr;
}

// Its parameter `name`; a test failure (and 0) when it has none.
inline double param(const discovery::Finding& f, const std::string& name) {
  for (const auto& [n, v] : f.params)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return 0.0;
}

}  // namespace knoblab::test
