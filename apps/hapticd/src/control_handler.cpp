#include "knoblab/hapticd/control_handler.hpp"

#include <cmath>
#include <cstdio>
#include <string_view>
#include <thread>
#include <variant>

#include "knoblab/hapticd/daemon.hpp"
#include "knoblab/hapticd/render_effects.hpp"
#include "short_number.hpp"
#include "knoblab/hapticd/tiles_json.hpp"
#include "knoblab/rt/timing_stats.hpp"
#include "knoblab/modbus/status_bits.hpp"

namespace knoblab::hapticd {

namespace {

using control::ErrorCode;
using control::Reply;
using nlohmann::json;
using detail::short_number;

json fault_names(std::uint32_t f) {
  json out = json::array();
  for (const FaultName& n : kFaultNames)
    if (f & n.bit) out.push_back(n.name);
  return out;
}

double get(const json& args, const char* key, double fallback) {
  return args.contains(key) ? args.at(key).get<double>() : fallback;
}

json stats_json(const fit::ErrorStats& s) {
  return {{"n", s.n}, {"mean", s.mean}, {"sd", s.sd}, {"mean_ci95", s.mean_ci95}};
}

// The event payload of a finished calibration (and get_state's copy).
json calibration_json(const CalibrationResult& r) {
  json j;
  j["kind"] = to_string(r.kind);
  j["ok"] = r.ok();
  if (!r.ok()) j["error"] = r.error;
  j["complete"] = r.complete;
  j["samples"] = r.cycles;
  j["torque_limited"] = r.torque_limited;
  json t4 = json::object();  // thesis Table 4: commanded − measured
  if (r.table4.theta.n) t4["theta"] = stats_json(r.table4.theta);
  if (r.table4.omega.n) t4["omega"] = stats_json(r.table4.omega);
  if (r.table4.alpha.n) t4["alpha"] = stats_json(r.table4.alpha);
  if (r.table4.torque.n) t4["torque"] = stats_json(r.table4.torque);
  j["table4"] = t4;
  if (r.accel)
    j["accel_gain"] = {{"C_cal", r.accel->C_cal}, {"C_cal_se", r.accel->C_cal_se},
                       {"C_cal_ci95", r.accel->C_cal_ci95}, {"residual_sd", r.accel->residual_sd},
                       {"n", r.accel->n}, {"dof", r.accel->dof}};
  if (r.gravity)
    j["gravity"] = {{"A", r.gravity->A}, {"B", r.gravity->B}, {"C", r.gravity->C}, {"D", r.gravity->D},
                    {"A_se", r.gravity->A_se}, {"D_se", r.gravity->D_se}, {"C_se", r.gravity->C_se},
                    {"A_ci95", r.gravity->A_ci95}, {"D_ci95", r.gravity->D_ci95},
                    {"C_ci95", r.gravity->C_ci95},
                    {"cw", {{"A", r.gravity->cw.A}, {"C", r.gravity->cw.C}, {"D", r.gravity->cw.D}}},
                    {"ccw", {{"A", r.gravity->ccw.A}, {"C", r.gravity->ccw.C}, {"D", r.gravity->ccw.D}}}};
  j["calibration"] = json::parse(r.updated.to_json());  // the constants with the fit applied
  return j;
}

}  // namespace

// Loop statistics once a second, for a status strip or a log.
void ControlHandler::publish_stats(control::Server& server) {
  const auto now = std::chrono::steady_clock::now();
  if (now < next_stats_) return;
  next_stats_ = now + std::chrono::seconds(1);
  const rt::TimingStats raw = daemon_.stats().read();
  const rt::TimingSummary t = rt::summarize(raw);
  const RecorderStats r = daemon_.recorder_stats();
  // Wake-up latency since start on doubling bins from 1 µs, for a display.
  const rt::DoublingBins bins = rt::doubling_bins(raw.wakeup.bins(), rt::WakeupHistogram::kBinNs, 1000);
  json upper = json::array();
  for (const std::int64_t ns : bins.upper_ns) upper.push_back(static_cast<double>(ns) * 1e-3);
  server.publish({"stats",
                  {{"cycles", t.cycles},
                   {"rate_hz", daemon_.config().core.rate_hz},
                   {"overruns", t.overruns},
                   {"max_consecutive_overruns", t.max_consecutive_overruns},
                   {"wakeup_latency_us", {{"p99", static_cast<double>(t.wakeup.p99_ns) * 1e-3},
                                          {"max", static_cast<double>(t.wakeup.max_ns) * 1e-3}}},
                   {"cycle_cost_us", {{"p99", static_cast<double>(t.compute.p99_ns) * 1e-3},
                                      {"max", static_cast<double>(t.compute.max_ns) * 1e-3}}},
                   {"wakeup_histogram_us", {{"upper", upper}, {"counts", bins.counts}}},
                   {"ring_dropped", daemon_.ring_dropped()},
                   {"recorder_buffered", r.buffered}}});
}

json ControlHandler::state_json() const {
  const CoreState s = daemon_.core().state();
  json j;
  j["mode"] = to_string(s.mode);
  j["faults"] = fault_names(s.faults);
  j["recording"] = s.recording_id != 0;
  j["cycles"] = s.cycles;
  j["capture_button_presses"] = s.button_presses;
  j["rate_hz"] = daemon_.config().core.rate_hz;
  j["hand_channel"] = daemon_.config().hand_channel.empty() ? json(nullptr) : json(daemon_.config().hand_channel);
  j["modbus"] = modbus::status::describe(daemon_.modbus_status());
  j["ring_dropped"] = daemon_.ring_dropped();
  // The overruns fault's evidence, also when the fault is latched or gone:
  // cycles that outlasted their period, the longest run of them, the limit.
  const rt::TimingSummary t = rt::summarize(daemon_.stats().read());
  j["overruns"] = {{"total", t.overruns},
                   {"max_consecutive", t.max_consecutive_overruns},
                   {"limit", daemon_.config().core.limits.max_consecutive_overruns}};
  j["tiles"] = tiles_;
  const RecorderStats r = daemon_.recorder_stats();
  j["recorder"] = {{"buffered", r.buffered}, {"max_buffered", r.max_buffered}, {"capacity", r.capacity},
                   {"retries", r.retries}, {"failed", r.failed}};
  if (const auto cal = daemon_.last_calibration()) j["last_calibration"] = calibration_json(*cal);
  // The constants in use and when each kind was last accepted (its age).
  j["calibration"] = {{"constants", json::parse(daemon_.sensor_calibration().to_json())},
                      {"accepted", daemon_.accepted_calibrations()}};
  return j;
}

RenderParams render_params_from_args(const json& a, RenderParams base, bool partial) {
  RenderParams p = partial ? base : RenderParams{};
  p.M_acc = get(a, "M_acc", p.M_acc);
  p.B_vel = get(a, "B_vel", p.B_vel);
  p.A_pos = get(a, "A_pos", p.A_pos);
  p.P_pos = get(a, "P_pos", p.P_pos);
  if (a.contains("dv")) {
    p.stick = true;
    p.dv = get(a, "dv", p.dv);
    p.D_neg = get(a, "D_neg", p.D_neg);
    p.D_pos = get(a, "D_pos", p.D_pos);
  } else if (!partial) {
    p.stick = false;
  }
  p.K_vm = get(a, "K_vm", p.K_vm);
  p.B_vm = get(a, "B_vm", p.B_vm);
  if (a.contains("effects")) p.effects = effects_from_args(a.at("effects"));
  else if (!partial) p.effects = {};
  return p;
}

std::optional<ParamProblem> render_params_problem(const RenderParams& p, const SafetyLimits& limits) {
  const std::pair<const char*, double> values[] = {{"M_acc", p.M_acc}, {"B_vel", p.B_vel}, {"A_pos", p.A_pos},
                                                   {"P_pos", p.P_pos}, {"dv", p.dv},       {"D_neg", p.D_neg},
                                                   {"D_pos", p.D_pos}, {"K_vm", p.K_vm},   {"B_vm", p.B_vm}};
  for (const auto& [key, v] : values) {
    if (!std::isfinite(v)) return ParamProblem{key, std::string(key) + " is not a finite number"};
    // A detent amplitude's sign is its phase; everything else is a physical
    // magnitude that would feed energy in if negative.
    if (std::string_view(key) != "A_pos" && v < 0.0)
      return ParamProblem{key, std::string(key) + " = " + short_number(v) + " is negative: it would feed energy into the knob"};
  }
  if (!(p.P_pos > 0.0)) return ParamProblem{"P_pos", "P_pos must be positive (the detent period)"};
  const double limit = limits.torque_limit_Nm;
  const auto beyond = [&](const char* key, double torque) -> std::optional<ParamProblem> {
    if (std::abs(torque) <= limit) return std::nullopt;
    return ParamProblem{key, std::string(key) + " = " + short_number(torque * 1e3) +
                                 " mN·m is beyond the device's torque limit of " + short_number(limit * 1e3) +
                                 " mN·m"};
  };
  if (auto b = beyond("A_pos", p.A_pos)) return b;
  if (p.stick) {
    if (auto b = beyond("D_neg", p.D_neg)) return b;
    if (auto b = beyond("D_pos", p.D_pos)) return b;
  }
  return effects_problem(p.effects, limits);
}

Reply ControlHandler::render(const json& a, bool partial) {
  const RenderParams p = render_params_from_args(a, params_, partial);
  if (const auto problem = render_params_problem(p, daemon_.config().core.limits))
    return Reply::failure(ErrorCode::bad_args, problem->message, problem->key);
  CoreCommand c;
  c.kind = CoreCommand::SetRender;
  c.render = p;
  if (!daemon_.post(c)) return Reply::failure(ErrorCode::busy, "the loop is not taking commands");
  params_ = p;
  return Reply::success({{"ramp_s", kParamRampSeconds}});
}

Reply ControlHandler::load_tiles(const json& a) {
  auto parsed = tiles_from_json(a, daemon_.config().core.limits,
                                RenderController::loop_dynamics(daemon_.config().core.rate_hz));
  if (auto* problem = std::get_if<ParamProblem>(&parsed))
    return Reply::failure(ErrorCode::bad_args, problem->message, problem->key);
  auto& set = std::get<std::unique_ptr<TileSet>>(parsed);
  const json counts = {{"position", set->position.size()}, {"time", set->time.size()}};
  if (set->position.empty() && set->time.empty()) set.reset();  // {} clears
  // The loop takes an offered set every cycle once the fade before it is
  // over; a load right after another waits for that (up to the fades of the
  // two before it, kParamRampSeconds each).
  const int attempts = 100 + static_cast<int>(2000.0 * kParamRampSeconds);  // 1 ms apart
  for (int attempt = 0; !daemon_.core().load_tiles(std::move(set)); ++attempt) {
    if (attempt == attempts) return Reply::failure(ErrorCode::busy, "the loop is not taking tiles (is it running?)");
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  tiles_ = counts;
  return Reply::success(counts);
}

Reply ControlHandler::start_trial(const json& a) {
  const json trial = {{"study", a.at("study")}, {"participant", a.at("participant")},
                      {"condition", a.at("condition")}};
  std::string why;
  const auto id = daemon_.start_trial(trial, why);
  if (!id) return Reply::failure(ErrorCode::busy, why);
  trial_id_ = *id;
  trial_ = trial;
  pending_trial_events_.push_back({"trial", {{"state", "started"}, {"trial", trial}}});
  return Reply::success();
}

Reply ControlHandler::start_capture(const json& a) {
  capture::CaptureConfig cc;
  if (a.contains("torque_sweep")) {  // open-loop torque chirp (schema: exactly one stimulus)
    const json& s = a.at("torque_sweep");
    cc.kind = capture::CaptureConfig::Stimulus::Torque;
    cc.torque_stimulus = {s.at("a").get<double>(), s.at("b").get<double>(), s.at("c").get<double>(),
                          s.at("d").get<double>()};
    cc.torque_per_volt = daemon_.config().core.limits.torque_per_volt;
  } else {
    const json& s = a.at("swept_sine");
    cc.stimulus = {s.at("a").get<double>(), s.at("b").get<double>(), s.at("c").get<double>(),
                   s.at("d").get<double>()};
  }
  if (a.contains("pid")) {
    const json& pid = a.at("pid");
    cc.pid.Kp = get(pid, "Kp", cc.pid.Kp);
    cc.pid.Ki = get(pid, "Ki", cc.pid.Ki);
    cc.pid.Kd = get(pid, "Kd", cc.pid.Kd);
  }
  CaptureLabels labels;
  labels.knob = a.at("knob").get<std::string>();
  labels.mounting = a.value("mounting", "lab");
  if (a.contains("gripper")) labels.metadata["gripper"] = a.at("gripper");
  if (a.contains("notes")) labels.metadata["notes"] = a.at("notes");
  // A capture shorter than one cycle would record nothing and never finish.
  const double seconds = a.at("seconds").get<double>();
  const auto samples = static_cast<std::int64_t>(std::llround(seconds * daemon_.config().core.rate_hz));
  if (samples < 1) {
    char why[96];
    std::snprintf(why, sizeof why, "is shorter than one cycle of the %g Hz loop: no sample would be taken",
                  daemon_.config().core.rate_hz);
    return Reply::failure(ErrorCode::bad_args, why, "seconds");
  }
  std::string why;
  if (!daemon_.start_capture(cc, seconds, labels, why)) return Reply::failure(ErrorCode::busy, why);
  return Reply::success({{"samples", samples}});
}

// The core refuses these too; saying so here tells the client why.
std::optional<Reply> ControlHandler::refused_while_faulted() const {
  const std::uint32_t faults = daemon_.core().state().faults;
  if (faults == 0) return std::nullopt;
  return Reply::failure(ErrorCode::busy, "a fault is latched (" + fault_list(faults) + "); clear_fault first");
}

Reply ControlHandler::handle(const control::Request& r) {
  std::lock_guard lock(mutex_);
  using control::Command;
  CoreCommand c;
  switch (r.command) {
    case Command::get_state:
      return Reply::success(state_json());
    case Command::load_model:
      return render(r.args, false);
    case Command::set_params:
      return render(r.args, true);
    case Command::start_capture:
      return start_capture(r.args);
    case Command::stop_capture:
      c.kind = CoreCommand::StopCapture;
      break;
    case Command::start_trial:
      return start_trial(r.args);
    case Command::load_tiles:
      return load_tiles(r.args);
    case Command::accept_calibration: {
      const auto kind = parse_calibration_kind(r.args.at("kind").get<std::string>());
      if (!kind) return Reply::failure(ErrorCode::bad_args, "unknown calibration kind", "kind");
      auto accepted = daemon_.accept_calibration(*kind, r.args.value("repetitions", 3));
      if (const auto* why = std::get_if<std::string>(&accepted)) return Reply::failure(ErrorCode::busy, *why);
      json result = to_json(std::get<AcceptedCalibration>(accepted));
      result["calibration"] = json::parse(daemon_.sensor_calibration().to_json());
      result["saved_to"] = daemon_.config().calibration_file.empty()
                               ? json(nullptr)
                               : json(daemon_.config().calibration_file.string());
      return Reply::success(result);
    }
    case Command::stop_trial:
      if (trial_id_ == 0) return Reply::failure(ErrorCode::busy, "no trial is running");
      c.kind = CoreCommand::StopRecording;
      break;
    case Command::clear_fault:
      if (!daemon_.clear_faults()) return Reply::failure(ErrorCode::busy, "the loop is not taking commands");
      return Reply::success({{"faults", fault_names(daemon_.core().state().faults)}});
    case Command::set_mode: {
      const std::string mode = r.args.at("mode").get<std::string>();
      if (mode == "capture") return Reply::failure(ErrorCode::bad_args, "captures start with start_capture", "mode");
      if (mode == "calibrate")
        return Reply::failure(ErrorCode::bad_args, "calibrations start with calibrate", "mode");
      c.kind = CoreCommand::SetMode;
      c.mode = mode == "render" ? Mode::Render : Mode::Idle;
      if (c.mode == Mode::Render)
        if (const auto why = refused_while_faulted()) return *why;
      break;
    }
    case Command::calibrate: {
      const auto kind = parse_calibration_kind(r.args.at("kind").get<std::string>());
      if (!kind) return Reply::failure(ErrorCode::bad_args, "unknown calibration kind", "kind");
      CalibrationConfig cc;  // thesis durations: 5 s sweeps, ~16 s a revolution each way
      cc.kind = *kind;
      cc.sweep_seconds = get(r.args, "sweep_seconds", cc.sweep_seconds);
      cc.gravity_seconds = get(r.args, "gravity_seconds", cc.gravity_seconds);
      cc.gravity_ramp_seconds = get(r.args, "gravity_ramp_seconds", cc.gravity_ramp_seconds);
      if (r.args.contains("pid")) {
        const json& pid = r.args.at("pid");
        cc.pid.Kp = get(pid, "Kp", cc.pid.Kp);
        cc.pid.Ki = get(pid, "Ki", cc.pid.Ki);
        cc.pid.Kd = get(pid, "Kd", cc.pid.Kd);
      }
      double seconds = 0.0;
      std::string why;
      if (!daemon_.start_calibration(cc, seconds, why)) return Reply::failure(ErrorCode::busy, why);
      return Reply::success({{"kind", to_string(*kind)},
                             {"seconds", seconds},
                             {"samples", static_cast<std::int64_t>(
                                             std::llround(seconds * daemon_.config().core.rate_hz))},
                             {"event", "calibration_finished"}});
    }
    default:
      return Reply::failure(ErrorCode::internal, "command not handled by hapticd");
  }
  if (!daemon_.post(c)) return Reply::failure(ErrorCode::busy, "the loop is not taking commands");
  return Reply::success();
}

void ControlHandler::on_watchdog_expired(control::WatchdogReason) { daemon_.force_safe(kFaultWatchdog); }

void ControlHandler::publish_events(control::Server& server, const std::vector<FinishedRecording>& finished) {
  std::lock_guard lock(mutex_);
  const CoreState s = daemon_.core().state();
  if (s.faults != last_faults_) {
    if (s.faults & ~last_faults_) server.publish({"fault_latched", {{"faults", fault_names(s.faults)}}});
    last_faults_ = s.faults;
    server.publish({"state", state_json()});
  } else if (static_cast<int>(s.mode) != last_mode_) {
    server.publish({"state", state_json()});
  }
  last_mode_ = static_cast<int>(s.mode);
  // Presses are only reported: what one means (start a capture, go on to the
  // next step) is up to the front-end, which knows the knob and labels.
  if (s.button_presses > last_presses_) {
    server.publish({"capture_button", {{"presses", s.button_presses}, {"new", s.button_presses - last_presses_}}});
    last_presses_ = s.button_presses;
  }
  for (control::Event& e : pending_trial_events_) server.publish(std::move(e));
  pending_trial_events_.clear();
  for (const FinishedRecording& f : finished) {
    if (f.recording_id == trial_id_ && trial_id_ != 0) {
      server.publish({"trial", {{"state", "stopped"},
                                {"trial", trial_},
                                {"capture_id", f.capture_id},
                                {"samples", f.samples},
                                {"complete", f.complete},
                                {"end_reason", f.end_reason}}});
      trial_id_ = 0;
    }
  }
  publish_stats(server);
  for (const FinishedRecording& f : finished)
    server.publish({"capture_finished",
                    {{"capture_id", f.capture_id},
                     {"kind", to_string(f.kind)},
                     {"samples", f.samples},
                     {"complete", f.complete},
                     {"end_reason", f.end_reason}}});
  if (const auto cal = daemon_.take_finished_calibration())
    server.publish({"calibration_finished", calibration_json(*cal)});
}

}  // namespace knoblab::hapticd
