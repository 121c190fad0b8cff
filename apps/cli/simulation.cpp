#include "simulation.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "knoblab/hapticd/sim_time_loop.hpp"
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

// x to `digits` significant digits, rounded towards zero: a bound stays a bound.
std::string down(double x, int digits = 4) {
  if (x == 0.0 || !std::isfinite(x)) return approx(x);
  const int last = static_cast<int>(std::floor(std::log10(std::abs(x)))) - (digits - 1);  // 10^last: last digit kept
  const double q = std::pow(10.0, last);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -last), std::trunc(x / q) * q);
  std::string out = buf;
  if (out.find('.') != std::string::npos) {
    out.erase(out.find_last_not_of('0') + 1);  // 60.00 → 60., 429.70 → 429.7
    if (out.back() == '.') out.pop_back();
  }
  return out;
}

std::string percent(double fraction) { return approx(100.0 * fraction) + " %"; }

// What to change so that the sweep stays at or below f_ok Hz: a capture
// that ends before it gets there, or one as long that sweeps slower.
std::string slower(const model::SweptSine& sw, double seconds, double f_ok) {
  std::string out;
  const double t_ok = sw.time_at_peak_speed(2.0 * std::numbers::pi * std::abs(sw.c) * f_ok);
  if (t_ok >= 0.5 && t_ok < seconds) out = "--seconds " + down(t_ok, 2) + " or less";
  const double f0 = std::abs(sw.frequency_hz(0.0));
  if (f0 < 0.9 * f_ok) {
    if (!out.empty()) out += ", or ";
    out += "a slower sweep such as --sweep " + down(f0 * seconds) + "," + down(f_ok * seconds) + "," +
           down(sw.c) + "," + down(seconds) + " (" + approx(f0) + " Hz to " + down(f_ok) + " Hz over " +
           down(seconds) + " s)";
  }
  if (!out.empty()) out += ", or ";
  return out + "a smaller amplitude";
}

// Why a simulated capture stopped at sample `cut`, and what to change.
std::string cut_message(const SimulationRequest& r, const interchange::Capture& cap, std::size_t cut,
                        std::uint32_t faults, std::int64_t cycles, const hapticd::SafetyLimits& limits,
                        const capture::CaptureController& controller) {
  const model::SweptSine& sw = r.stimulus;
  const double t = cap.t[cut];
  const double f = sw.frequency_hz(t);
  std::string m = "the capture stopped at t = " + approx(t) + " s (sample " + std::to_string(cut + 1) + " of " +
                  std::to_string(cycles) + ") on a safety fault (" +
                  (faults != 0 ? hapticd::fault_list(faults) : std::string("none latched, yet the motor was off")) +
                  ")";
  if (cut + 1 < cap.size())
    m += " and went on recording " + std::to_string(cap.size() - cut - 1) + " samples with the motor held safe";
  m += ": ";
  const std::string sweep_there = approx(f) + " Hz with " + approx(sw.c) + " rad amplitude";
  if (faults & hapticd::kFaultTracking) {
    const capture::TrackingLimits& tl = controller.config().tracking;
    m += "the knob was more than " + approx(controller.tracking_threshold_rad()) + " rad off the sweep (" +
         percent(tl.fraction) + " of its amplitude, at least " + approx(tl.floor_rad) + " rad) for " +
         approx(tl.hold_s * 1e3) + " ms running (at the end " + approx(cap.theta[cut]) + " rad, the sweep " +
         approx(cap.theta.front() + sw.theta(t)) + " rad)";
    // Did the motor run out of torque? The second before says.
    std::size_t n = 0, limited = 0;
    for (std::size_t i = cut + 1; i-- > 0 && cap.t[i] > t - 1.0;) {
      ++n;
      if (cap.flags[i] & interchange::kTorqueLimited) ++limited;
    }
    if (limited != 0) {
      m += "; in the second before, the command sat at the " + approx(limits.torque_limit_Nm * 1e3) +
           " mN·m torque limit in " + percent(static_cast<double>(limited) / static_cast<double>(n)) +
           " of the samples: the sweep there runs at " + sweep_there +
           ", more than this knob can be driven through. Change to ";
    } else {
      m += " with the command inside the torque limit: the PID lost the knob (the sweep there runs at " +
           sweep_there + "); check --kp, --ki, --kd and the effects (walls, play), or change to ";
    }
    // Where tracking still held with room to spare.
    m += slower(sw, r.seconds, std::abs(sw.frequency_hz(0.8 * t)));
  } else if (faults & hapticd::kFaultVelocity) {
    const double vlim = limits.velocity_limit_rad_s;
    const double v = sw.peak_speed(t);
    m += "the knob passed the " + approx(vlim) + " rad/s velocity limit";
    if (v >= 0.8 * vlim) {
      m += " where the sweep runs at " + sweep_there + ", up to " + approx(v) + " rad/s";
      const double t_lim = sw.time_at_peak_speed(vlim);
      if (t_lim > t && t_lim <= r.seconds)
        m += ", and reaches the limit itself at t = " + approx(t_lim) + " s (Eq. 8's frequency rises by " +
             approx((sw.b - sw.a) / (sw.d * sw.d)) + " Hz every second, past t = d too)";
      m += ". Keep the sweep under " + approx(0.9 * vlim) + " rad/s: change to " +
           slower(sw, r.seconds, 0.9 * vlim / (2.0 * std::numbers::pi * std::abs(sw.c)));
    } else {
      m += ", yet the sweep there peaks at " + approx(v) + " rad/s (" + approx(f) +
           " Hz): the knob ran away from the PID; check --kp, --ki, --kd and the knob's parameters";
    }
  } else {
    m += "the supervisor held the motor safe; the sweep (" + sweep_there + " there) does not explain it";
  }
  return m;
}

}  // namespace

SimulationResult simulate(const SimulationRequest& request, store::Store* db) {
  // Knob terms (spring, detent shape, walls, backlash, presliding) fold into
  // the knob, rig effects (compliance, delay, clipping) into the plant's
  // config, the rest are knob torques on the plant. The metadata lists all.
  SimulationRequest r = request;
  std::vector<const model::EffectSpec*> rest;
  for (const model::EffectSpec& e : request.effects)
    if (!sim::apply_to_knob(e, r.knob)) rest.push_back(&e);
  validate(r);
  sim::PlantConfig plant = plant_config(r);
  std::vector<const model::EffectSpec*> torques;
  for (const model::EffectSpec* e : rest)
    if (!sim::apply_to_plant(*e, plant)) torques.push_back(e);
  // hapticd's cycle, run back to back in simulated time: the same core, modes
  // and supervisor the realtime daemon runs.
  hapticd::SimTimeLoop loop(plant, r.rate_hz);
  for (const model::EffectSpec* e : torques) loop.daq().plant().add_effect(sim::make_knob_effect(*e));

  capture::CaptureConfig cfg;
  cfg.rate_hz = r.rate_hz;
  cfg.stimulus = r.stimulus;
  cfg.pid = r.pid;
  const capture::SensorCalibration calibration = loop.daq().calibration();
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
    for (const model::EffectSpec& e : r.effects) list += (list.empty() ? "" : ";") + e.text();
    cap.metadata.emplace_back("effects", list);
  }
  cap.has_command = true;
  for (auto* v : {&cap.t, &cap.theta, &cap.omega, &cap.alpha, &cap.torque, &cap.command})
    v->reserve(static_cast<std::size_t>(cycles));
  cap.flags.reserve(static_cast<std::size_t>(cycles));

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

  hapticd::CoreCommand start;
  start.kind = hapticd::CoreCommand::StartCapture;
  start.capture = controller;
  start.capture_cycles = cycles;
  loop.post(start);

  // The first sample the supervisor held safe (or the e-stop was asserted,
  // or the amplifier was off): the capture is cut there, whatever follows.
  constexpr std::uint32_t kUnsafe = interchange::kFaultLatched | interchange::kEstopActive;
  std::optional<std::size_t> cut;
  std::uint32_t cut_faults = 0;
  double sq_err = 0.0;
  constexpr std::int64_t kChunk = 1000;  // cycles between looks at the hooks
  for (std::int64_t i = 0; i <= cycles; ++i) {
    if (i % kChunk == 0) {
      r.hooks.report("simulating", static_cast<std::size_t>(i), static_cast<std::size_t>(cycles));
      if (r.hooks.cancelled && r.hooks.cancelled()) {
        if (writer) writer->discard();  // nothing of a cancelled capture stays
        throw fit::Cancelled();
      }
    }
    const hapticd::LoopRecord& rec = loop.step();
    if (rec.recording_id == 0) continue;
    const capture::Sample& s = rec.sample;
    if (!cut && ((s.flags & kUnsafe) != 0 || (s.flags & interchange::kAmpEnabled) == 0)) {
      cut = cap.t.size();
      cut_faults = rec.faults;
    }
    cap.t.push_back(s.t);
    cap.theta.push_back(s.theta);
    cap.omega.push_back(s.omega);
    cap.alpha.push_back(s.alpha);
    cap.torque.push_back(s.torque);
    cap.command.push_back(s.command);
    cap.flags.push_back(s.flags);
    // The capture centres the sweep where the knob stood at its first sample.
    const double e = cap.theta.front() + r.stimulus.theta(s.t) - s.theta;
    sq_err += e * e;
    result.max_command_V = std::max(result.max_command_V, std::abs(s.command));
    if (writer) writer->append(s);
  }
  result.tracking_rms_rad = std::sqrt(sq_err / static_cast<double>(std::max<std::size_t>(cap.size(), 1)));
  if (cut) {
    const std::string why = cut_faults != 0 ? "fault: " + hapticd::fault_list(cut_faults) : "motor not driven";
    const std::string message = cut_message(r, cap, *cut, cut_faults, cycles, loop.core().config().limits, controller);
    cap.metadata.emplace_back("status", "incomplete");
    cap.metadata.emplace_back("end_reason", why);
    if (writer) {
      writer->finish_incomplete(why);
      result.capture_id = writer->capture_id();
    }
    throw CaptureFailed(message, std::move(result));
  }
  if (static_cast<std::int64_t>(cap.t.size()) != cycles)
    throw std::logic_error("the capture recorded " + std::to_string(cap.t.size()) + " of " +
                           std::to_string(cycles) + " samples");
  if (writer) {
    writer->finish();
    result.capture_id = writer->capture_id();
  }
  return result;
}

}  // namespace knoblab::cli
