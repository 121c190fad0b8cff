#include "knoblab/studyrun/core_apparatus.hpp"

#include <cmath>
#include <stdexcept>

#include "knoblab/hapticd/sim_time_loop.hpp"
#include "knoblab/hapticd/supervisor.hpp"
#include "knoblab/sim/presets.hpp"
#include "render_terms.hpp"

namespace knoblab::studyrun {

struct CoreApparatus::Impl {
  Impl(const sim::presets::Preset& preset, double rate) : loop(config(preset), rate) {
    loop.daq().plant().add_effect(sim::make_guided_hand(hand));
    cycles_per_reading = std::max<long>(1, std::lround(rate / 1000.0));
  }
  static sim::PlantConfig config(const sim::presets::Preset& preset) {
    sim::PlantConfig c;
    c.knob = preset.knob;
    return c;
  }
  void post(const hapticd::CoreCommand& c) {
    if (!loop.post(c)) throw ApparatusError("hapticd's core did not take a command (its queue is full)");
  }

  sim::HandChannel hand;
  hapticd::SimTimeLoop loop;
  long cycles_per_reading = 1;
  bool render_mode = false;
};

CoreApparatus::CoreApparatus(const std::string& knob, double rate_hz) {
  const sim::presets::Preset* preset = sim::presets::find(knob);
  if (!preset) throw std::invalid_argument("no sim knob preset '" + knob + "' (knoblab simulate --list)");
  if (!(rate_hz >= 1000 && rate_hz <= 100000)) throw std::invalid_argument("the loop rate must be 1–100 kHz");
  impl_ = std::make_unique<Impl>(*preset, rate_hz);
}

CoreApparatus::~CoreApparatus() = default;

sim::HandChannel& CoreApparatus::hand() { return impl_->hand; }

void CoreApparatus::render(const study::Rendering& r) {
  hapticd::CoreCommand c;
  c.kind = hapticd::CoreCommand::SetRender;
  const detail::RenderTerms t = detail::render_terms(r);
  c.render.M_acc = t.M_acc;
  c.render.B_vel = t.B_vel;
  c.render.A_pos = t.A_pos;
  c.render.P_pos = t.P_pos;
  impl_->post(c);
  if (!impl_->render_mode) {
    hapticd::CoreCommand m;
    m.kind = hapticd::CoreCommand::SetMode;
    m.mode = hapticd::Mode::Render;
    impl_->post(m);
    impl_->render_mode = true;
  }
}

void CoreApparatus::start_trial(const TrialLabel&) {
  hapticd::CoreCommand c;
  c.kind = hapticd::CoreCommand::StartRecording;
  impl_->post(c);
}

TrialRecording CoreApparatus::stop_trial() {
  hapticd::CoreCommand c;
  c.kind = hapticd::CoreCommand::StopRecording;
  impl_->post(c);
  return {.capture_id = std::nullopt, .complete = true, .end_reason = ""};
}

KnobReading CoreApparatus::next() {
  hapticd::LoopRecord rec;
  for (long i = 0; i < impl_->cycles_per_reading; ++i) rec = impl_->loop.step();
  if (rec.faults != 0) {
    impl_->render_mode = false;
    throw ApparatusError("hapticd's core latched a fault (" + hapticd::fault_list(rec.faults) + ")");
  }
  return {rec.sample.t, rec.sample.theta, rec.sample.omega, rec.sample.torque};
}

}  // namespace knoblab::studyrun
