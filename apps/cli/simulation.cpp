#include "simulation.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hapticd/core.hpp"
#include "knoblab/interchange/number_text.hpp"
#include "knoblab/sim/knob.hpp"

namespace knoblab::cli {

namespace {

std::string fmt(double x) { return interchange::shortest(x); }
std::string approx(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

std::string stimulus_json(const model::SweptSine& s) {
  return "{\"kind\": \"swept_sine\", \"equation\": 8, \"a\": " + fmt(s.a) + ", \"b\": " + fmt(s.b) +
         ", \"c\": " + fmt(s.c) + ", \"d\": " + fmt(s.d) + "}";
}

sim::PlantConfig plant_config(const SimulationRequest& r) {
  sim::PlantConfig c;
  c.knob = r.knob;
  c.seed = r.seed;
  c.amp.mode = r.amp;
  c.mounting = r.mode == "lab" ? sim::CameraOrientation::lab() : sim::CameraOrientation::tripod(r.tilt_rad);
  return c;
}

void validate(const SimulationRequest& r) {
  if (!(r.seconds > 0.0) || r.seconds > 3600.0)
    throw std::invalid_argument("--seconds must be in (0, 3600], got " + fmt(r.seconds));
  if (!(r.rate_hz >= 1.0) || r.rate_hz > 20000.0)
    throw std::invalid_argument("--rate must be in [1, 20000] Hz, got " + fmt(r.rate_hz));
  if (r.mode != "lab" && r.mode != "tripod")
    throw std::invalid_argument("--mode must be 'lab' or 'tripod', got '" + r.mode + "'");
  if (const auto why = sim::check(r.knob); !why.empty())
    throw std::invalid_argument("knob '" + r.knob_name + "' is not physical: " + std::string(why));
}

}  // namespace

SimulationResult simulate(const SimulationRequest& request, store::Store* db) {
  // Knob terms (spring, detent shape, walls, backlash, presliding) fold into
  // the knob, rig effects (compliance, delay, clipping) into the plant's
  // config, the rest are knob torques on the plant. The metadata lists all.
  SimulationRequest r = request;
  std::vector<const sim::EffectSpec*> rest;
  for (const sim::EffectSpec& e : request.effects)
    if (!sim::apply_to_knob(e, r.knob)) rest.push_back(&e);
  validate(r);
  sim::PlantConfig plant = plant_config(r);
  std::vector<const sim::EffectSpec*> torques;
  for (const sim::EffectSpec* e : rest)
    if (!sim::apply_to_plant(*e, plant)) torques.push_back(e);
  capture::SimDaq daq(plant, r.rate_hz);
  for (const sim::EffectSpec* e : torques) daq.plant().add_effect(sim::make_knob_effect(*e));

  capture::CaptureConfig cfg;
  cfg.rate_hz = r.rate_hz;
  cfg.stimulus = r.stimulus;
  cfg.pid = r.pid;
  const capture::SensorCalibration calibration = daq.calibration();
  capture::CaptureController controller(cfg);

  const auto cycles = static_cast<std::int64_t>(std::llround(r.seconds * r.rate_hz));
  const std::string orientation = "{\"tilt_rad\": " + fmt(r.mode == "lab" ? std::numbers::pi / 2 : r.tilt_rad) + "}";

  SimulationResult result;
  interchange::Capture& cap = result.capture;
  cap.metadata = {{"source", "knoblab simulate"},     {"knob", r.knob_name},
                  {"mode", r.mode},                    {"rate_hz", fmt(r.rate_hz)},
                  {"seed", std::to_string(r.seed)},    {"stimulus", stimulus_json(r.stimulus)},
                  {"orientation", orientation},        {"calibration", calibration.to_json()}};
  if (!r.effects.empty()) {
    std::string list;
    for (const sim::EffectSpec& e : r.effects) list += (list.empty() ? "" : ";") + e.text();
    cap.metadata.emplace_back("effects", list);
  }
  cap.has_command = true;
  for (auto* v : {&cap.t, &cap.theta, &cap.omega, &cap.alpha, &cap.torque, &cap.command})
    v->reserve(static_cast<std::size_t>(cycles));

  std::optional<store::CaptureWriter> writer;
  if (db) {
    store::NewCapture info;
    info.knob = r.knob_name;
    info.mode = r.mode;
    info.rate_hz = r.rate_hz;
    info.stimulus = stimulus_json(r.stimulus);
    info.orientation = orientation;
    info.calibration = calibration.to_json();
    info.source = "simulate";
    info.has_command = true;
    info.metadata = "{\"seed\": " + std::to_string(r.seed) + "}";
    writer.emplace(db->begin_capture(info));
  }

  // hapticd's cycle, run back to back in simulated time: the same core, modes
  // and supervisor the realtime daemon runs.
  hapticd::CoreConfig core_cfg;
  core_cfg.rate_hz = r.rate_hz;
  core_cfg.calibration = calibration;
  hapticd::HapticCore core(core_cfg);
  hapticd::CoreCommand start;
  start.kind = hapticd::CoreCommand::StartCapture;
  start.capture = controller;
  start.capture_cycles = cycles;
  core.post(start);

  double sq_err = 0.0;
  hapticd::LoopRecord last{};
  for (std::int64_t i = 0; i <= cycles; ++i) {
    capture::DaqInputs in;
    capture::DaqOutputs out;
    hapticd::LoopRecord rec;
    // The simulated DAQ cannot fail unless a test makes it.
    hapticd::CycleContext ctx;
    ctx.io_ok = daq.read(in) == capture::IoStatus::ok;
    core.cycle(in, ctx, out, rec);
    (void)daq.write(out);
    if (rec.recording_id == 0) continue;
    last = rec;
    const capture::Sample& s = rec.sample;
    cap.t.push_back(s.t);
    cap.theta.push_back(s.theta);
    cap.omega.push_back(s.omega);
    cap.alpha.push_back(s.alpha);
    cap.torque.push_back(s.torque);
    cap.command.push_back(s.command);
    // The capture centres the sweep where the knob stood at its first sample.
    const double e = cap.theta.front() + r.stimulus.theta(s.t) - s.theta;
    sq_err += e * e;
    result.max_command_V = std::max(result.max_command_V, std::abs(s.command));
    if (writer) writer->append(s);
  }
  if (last.end == hapticd::RecordingEnd::fault) {
    // Say why and where, so the user can change the stimulus: a capture cut
    // by the supervisor is not a capture of the knob.
    const double f = r.stimulus.frequency_hz(last.sample.t);
    throw std::runtime_error("the capture stopped at t = " + approx(last.sample.t) + " s on a safety fault (" +
                             hapticd::fault_list(last.faults) + ") after " + std::to_string(cap.t.size()) + " of " +
                             std::to_string(cycles) + " samples; the sweep there runs at " + approx(f) + " Hz with " +
                             approx(r.stimulus.c) + " rad amplitude, up to " +
                             approx(2.0 * std::numbers::pi * f * r.stimulus.c) + " rad/s (velocity limit " +
                             approx(core_cfg.limits.velocity_limit_rad_s) + " rad/s): shorten it or slow the sweep");
  }
  if (static_cast<std::int64_t>(cap.t.size()) != cycles)
    throw std::logic_error("the capture recorded " + std::to_string(cap.t.size()) + " of " +
                           std::to_string(cycles) + " samples");
  if (writer) {
    writer->finish();
    result.capture_id = writer->capture_id();
  }
  result.tracking_rms_rad = std::sqrt(sq_err / static_cast<double>(std::max<std::int64_t>(cycles, 1)));
  return result;
}

}  // namespace knoblab::cli
