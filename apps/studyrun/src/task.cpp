#include "knoblab/studyrun/task.hpp"

#include "knoblab/studyrun/kind_tasks.hpp"
#include "knoblab/studyrun/pointing_task.hpp"

namespace knoblab::studyrun {

study::Rendering condition_rendering(const study::Protocol& protocol, const study::Trial& trial) {
  for (std::size_t f = 0; f < protocol.factors.size(); ++f)
    if (const auto& r = study::trial_level(protocol, trial, f).rendering) return *r;
  return {};
}

std::unique_ptr<Task> make_task(const study::Protocol& protocol, const study::Trial& trial, std::uint64_t trial_seed) {
  switch (protocol.kind) {
    case study::Kind::Pointing: return std::make_unique<PointingTask>(protocol, trial);
    case study::Kind::ListSelection: return std::make_unique<ListTask>(protocol, trial, trial_seed);
    case study::Kind::Matching: return std::make_unique<MatchingTask>(protocol, trial);
    case study::Kind::Textures: return std::make_unique<TextureTask>(protocol, trial);
  }
  throw std::invalid_argument("unknown study kind");
}

}  // namespace knoblab::studyrun
