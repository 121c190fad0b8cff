// THE table of protocol v1: every command's arguments. Ranges are the
// protocol's sanity bounds (a typo like 1e3 for 1e-3 never reaches the
// motor); the daemon may refuse narrower cases with its own bad_args.
#include <array>

#include "knoblab/control/schema.hpp"

namespace knoblab::control {

namespace {

constexpr bool kRequired = true;
constexpr bool kOptional = false;

constexpr ArgSpec number(std::string_view key, bool required, double lo, double hi,
                         std::string_view unit, std::string_view doc) {
  return {key, ArgType::number, required, {lo, hi}, {}, {}, nullptr, unit, doc};
}
constexpr ArgSpec integer(std::string_view key, bool required, double lo, double hi,
                          std::string_view unit, std::string_view doc) {
  return {key, ArgType::integer, required, {lo, hi}, {}, {}, nullptr, unit, doc};
}
constexpr ArgSpec text(std::string_view key, bool required, double max_len, std::string_view doc) {
  return {key, ArgType::string, required, {}, {1, max_len}, {}, nullptr, {}, doc};
}
constexpr ArgSpec label(std::string_view key, bool required, std::string_view doc) {
  return {key, ArgType::label, required, {}, {1, 128}, {}, nullptr, {}, doc};
}
constexpr ArgSpec boolean(std::string_view key, bool required, std::string_view doc) {
  return {key, ArgType::boolean, required, {}, {}, {}, nullptr, {}, doc};
}
constexpr ArgSpec choice(std::string_view key, bool required, std::span<const std::string_view> choices,
                         std::string_view doc) {
  return {key, ArgType::choice, required, {}, {}, choices, nullptr, {}, doc};
}
constexpr ArgSpec integer_list(std::string_view key, bool required, Range count, Range each,
                               std::string_view doc) {
  return {key, ArgType::integer_list, required, each, count, {}, nullptr, {}, doc};
}
constexpr ArgSpec choice_list(std::string_view key, bool required, Range count,
                              std::span<const std::string_view> choices, std::string_view doc) {
  return {key, ArgType::choice_list, required, {}, count, choices, nullptr, {}, doc};
}
constexpr ArgSpec object(std::string_view key, bool required, const ObjectSchema* schema,
                         std::string_view doc) {
  return {key, ArgType::object, required, {}, {}, {}, schema, {}, doc};
}
constexpr ArgSpec number_list(std::string_view key, bool required, Range count, Range each,
                              std::string_view unit, std::string_view doc) {
  return {key, ArgType::number_list, required, each, count, {}, nullptr, unit, doc};
}
constexpr ArgSpec object_list(std::string_view key, bool required, Range count, const ObjectSchema* schema,
                              std::string_view doc) {
  return {key, ArgType::object_list, required, {}, count, {}, schema, {}, doc};
}

template <std::size_t N>
constexpr std::array<ArgSpec, N> all_optional(std::array<ArgSpec, N> args) {
  for (auto& a : args) a.required = false;
  return args;
}

// hello
constexpr std::array kHelloArgs = {
    integer_list("versions", kRequired, {1, 16}, {1, 1000}, "protocol versions the client speaks"),
    text("client", kOptional, 64, "client name for logs, e.g. \"knoblab-ui\""),
    integer("watchdog_ms", kOptional, 10, 60000, "ms",
            "become the supervising client: silence this long (or disconnecting) puts "
            "the motor in its safe state"),
};

// load_model / set_params "effects": the effect library's terms the renderer
// can render (knoblab/model/effect_set.hpp), with the parameter names of the
// effect table (knoblab/model/effect_table.hpp): those discrepancy reports,
// a model file carries and `knoblab simulate --effects` takes.
constexpr std::array kOffsetArgs = {number("offset_Nm", kRequired, -0.5, 0.5, "N·m", "constant torque")};
constexpr std::array kGravityArgs = {
    number("amplitude_Nm", kRequired, -0.5, 0.5, "N·m", "once per revolution, τ = amplitude_Nm·sin(θ + phase_rad)"),
    number("phase_rad", kOptional, -1000, 1000, "rad", "its phase (default 0)"),
};
constexpr std::array kSpringArgs = {
    number("stiffness_Nm_per_rad", kOptional, -10, 10, "N·m/rad", "τ = K·(θ − θ₀) + K₃·(θ − θ₀)³"),
    number("cubic_Nm_per_rad3", kOptional, -1000, 1000, "N·m/rad³", "cubic stiffness K₃"),
    number("centre_rad", kOptional, -1000, 1000, "rad", "centre θ₀ (default 0)"),
};
constexpr std::array<std::string_view, 2> kSpringKeys = {"stiffness_Nm_per_rad", "cubic_Nm_per_rad3"};
constexpr std::array kSpringGroups = {GroupRule{GroupRule::Kind::at_least_one, kSpringKeys}};
constexpr std::array kPeriodicArgs = {
    number("amplitude_Nm", kRequired, -0.5, 0.5, "N·m", "τ = A·sin(2πθ/period_rad + phase_rad), a torque unrelated to the detents"),
    number("period_rad", kOptional, 0.006, 630, "rad", "period over position (default 2π: once per revolution)"),
    number("phase_rad", kOptional, -1000, 1000, "rad", "phase (default 0)"),
};
constexpr std::array kShapeArgs = {
    number("a2_Nm", kOptional, -0.5, 0.5, "N·m", "detent harmonics: Σ a_k·sin(kφ) + b_k·cos(kφ), φ = θ/P_pos"),
    number("b2_Nm", kOptional, -0.5, 0.5, "N·m", "2nd harmonic, cosine"),
    number("a3_Nm", kOptional, -0.5, 0.5, "N·m", "3rd harmonic, sine"),
    number("b3_Nm", kOptional, -0.5, 0.5, "N·m", "3rd harmonic, cosine"),
    number("a4_Nm", kOptional, -0.5, 0.5, "N·m", "4th harmonic, sine"),
    number("b4_Nm", kOptional, -0.5, 0.5, "N·m", "4th harmonic, cosine"),
};
constexpr std::array<std::string_view, 6> kShapeKeys = {"a2_Nm", "b2_Nm", "a3_Nm", "b3_Nm", "a4_Nm", "b4_Nm"};
constexpr std::array kShapeGroups = {GroupRule{GroupRule::Kind::at_least_one, kShapeKeys}};
constexpr std::array kStribeckArgs = {
    number("static_excess_Nm", kRequired, 0, 0.5, "N·m", "friction above its sliding level near zero speed"),
    number("stribeck_velocity_rad_s", kOptional, 1e-6, 100, "rad/s",
           "τ = sgn(θ̇)·ΔC·exp(−(θ̇/v_s)²), v_s this (default 1)"),
};
constexpr std::array kPowerDampingArgs = {
    number("coefficient", kRequired, 0, 1, "N·m·(s/rad)^p", "τ = sgn(θ̇)·c·abs(θ̇)^p, c this"),
    number("exponent", kOptional, 0.1, 4, "", "p (default 2)"),
};
constexpr std::array kEndstopArgs = {
    number("position_rad", kRequired, 0.001, 1000, "rad", "walls at ±position_rad"),
    number("stiffness_Nm_per_rad", kRequired, 0, 100, "N·m/rad", "beyond a wall, τ = stiffness·depth"),
    number("damping_Nm_s_per_rad", kOptional, 0, 1, "N·m·s/rad", "+ damping·θ̇ while inside a wall"),
    number("max_torque_Nm", kOptional, 0.0001, 0.5, "N·m",
           "the wall's torque tops out here (a rendered wall's plateau; default: it climbs on)"),
};
constexpr ObjectSchema kOffset{kOffsetArgs, {}};
constexpr ObjectSchema kGravity{kGravityArgs, {}};
constexpr ObjectSchema kSpring{kSpringArgs, kSpringGroups};
constexpr ObjectSchema kPeriodic{kPeriodicArgs, {}};
constexpr ObjectSchema kShape{kShapeArgs, kShapeGroups};
constexpr ObjectSchema kStribeck{kStribeckArgs, {}};
constexpr ObjectSchema kPowerDamping{kPowerDampingArgs, {}};
constexpr ObjectSchema kEndstop{kEndstopArgs, {}};
constexpr std::array kEffectsArgs = {
    object("offset", kOptional, &kOffset, "a constant torque (offset)"),
    object("gravity", kOptional, &kGravity, "a torque once per revolution (gravity)"),
    object("spring", kOptional, &kSpring, "a restoring spring (spring)"),
    object_list("periodic_torque", kOptional, {0, 4}, &kPeriodic, "position-periodic torques (periodic_torque)"),
    object("detent_shape", kOptional, &kShape, "harmonics 2…4 of the detents (detent_shape)"),
    object("stribeck", kOptional, &kStribeck, "Stribeck friction, outside the stick band (stribeck)"),
    object("nonlinear_damping", kOptional, &kPowerDamping, "power-law damping, outside the stick band"),
    object("endstop", kOptional, &kEndstop, "walls (endstop)"),
};
constexpr ObjectSchema kEffects{kEffectsArgs, {}};

// load_model / set_params: the render model (Eq. 14) plus options.
constexpr std::array kModelArgs = {
    number("M_acc", kRequired, 0, 0.01, "kg·m²", "inertia, τ = M_acc·θ̈"),
    number("B_vel", kRequired, 0, 1, "N·m·s/rad", "viscous damping, τ = B_vel·θ̇"),
    number("A_pos", kRequired, -0.5, 0.5, "N·m", "detent amplitude, τ = A_pos·sin(θ/P_pos)"),
    number("P_pos", kRequired, 0.001, 100, "rad", "detent period: 1/P_pos detents per revolution"),
    number("dv", kOptional, 0, 10, "rad/s", "stick band half-width (Karnopp, Eq. 7)"),
    number("D_neg", kOptional, 0, 0.5, "N·m", "static friction limit, negative torque"),
    number("D_pos", kOptional, 0, 0.5, "N·m", "static friction limit, positive torque"),
    number("K_vm", kOptional, 0, 100, "N·m/rad", "virtual-mass coupling stiffness"),
    number("B_vm", kOptional, 0, 1, "N·m·s/rad", "virtual-mass coupling damping"),
    object("effects", kOptional, &kEffects,
           "terms beyond Eq. 14 (knoblab discrepancy --model-out); set_params replaces the whole set"),
};
constexpr auto kParamArgs = all_optional(kModelArgs);
constexpr std::array<std::string_view, 3> kStickKeys = {"dv", "D_neg", "D_pos"};
constexpr std::array<std::string_view, 2> kVirtualMassKeys = {"K_vm", "B_vm"};
constexpr std::array<std::string_view, 10> kParamKeys = {
    "M_acc", "B_vel", "A_pos", "P_pos", "dv", "D_neg", "D_pos", "K_vm", "B_vm", "effects"};
constexpr std::array kModelGroups = {
    GroupRule{GroupRule::Kind::all_or_none, kStickKeys},
    GroupRule{GroupRule::Kind::all_or_none, kVirtualMassKeys},
};
constexpr std::array kParamGroups = {GroupRule{GroupRule::Kind::at_least_one, kParamKeys}};

// start_capture
constexpr std::array<std::string_view, 2> kMountings = {"lab", "tripod"};
constexpr std::array kSweptSineArgs = {
    number("a", kRequired, 0, 1000, "", "Eq. 8 sweep start (u at t = 0)"),
    number("b", kRequired, 0, 1000, "", "Eq. 8 sweep end (u at t = d)"),
    number("c", kRequired, 0, 6.3, "rad", "position amplitude"),
    number("d", kRequired, 0.01, 3600, "s", "sweep duration"),
};
constexpr std::array kTorqueSweepArgs = {
    number("a", kRequired, 0, 1000, "", "Eq. 8 sweep start (u at t = 0)"),
    number("b", kRequired, 0, 1000, "", "Eq. 8 sweep end (u at t = d)"),
    number("c", kRequired, 0, 0.5, "N·m", "torque amplitude"),
    number("d", kRequired, 0.01, 3600, "s", "sweep duration"),
};
constexpr std::array kPidArgs = {
    number("Kp", kOptional, 0, 1e5, "V/rad", "proportional gain (default 200)"),
    number("Ki", kOptional, 0, 1e7, "V/(rad·s)", "integral gain (default 5000)"),
    number("Kd", kOptional, 0, 100, "V·s/rad", "derivative gain (default 1)"),
};
constexpr ObjectSchema kSweptSine{kSweptSineArgs, {}};
constexpr ObjectSchema kTorqueSweep{kTorqueSweepArgs, {}};
constexpr ObjectSchema kPid{kPidArgs, {}};
constexpr std::array kCaptureArgs = {
    object("swept_sine", kOptional, &kSweptSine, "position stimulus θ = θ₀ + c·sin φ(t), Eq. 8, about the start angle θ₀"),
    object("torque_sweep", kOptional, &kTorqueSweep, "torque stimulus τ = c·sin φ(t)"),
    object("pid", kOptional, &kPid, "position controller gains (Eq. 4)"),
    number("seconds", kRequired, 0.01, 3600, "s", "capture length"),
    text("knob", kRequired, 64, "knob name the capture is stored under"),
    choice("mounting", kOptional, kMountings,
           "lab: the knob in the chuck; tripod: the camera on a tripod at the knob where it is (default lab)"),
    text("gripper", kOptional, 128, "how the knob is gripped, e.g. \"ABS print, VHB tape\" (stored with the capture)"),
    text("notes", kOptional, 512, "the experimenter's notes (stored with the capture)"),
};
constexpr std::array<std::string_view, 2> kStimulusKeys = {"swept_sine", "torque_sweep"};
constexpr std::array kCaptureGroups = {GroupRule{GroupRule::Kind::exactly_one, kStimulusKeys}};

// start_trial
constexpr std::array kTrialArgs = {
    label("study", kRequired, "study id (opaque)"),
    label("participant", kRequired, "participant id (opaque)"),
    label("condition", kRequired, "condition id (opaque)"),
};

// calibrate, set_mode
constexpr std::array<std::string_view, 4> kCalibrationKinds = {"spatial", "torque", "accel_gain",
                                                               "gravity"};
constexpr std::array kCalibrateArgs = {
    choice("kind", kRequired, kCalibrationKinds, "what to calibrate"),
    number("sweep_seconds", kOptional, 0.1, 600, "s", "spatial, torque, accel_gain: sweep length (default 5, Table 3)"),
    number("gravity_seconds", kOptional, 1, 600, "s", "gravity: one revolution each way in this time (default 16)"),
    number("gravity_ramp_seconds", kOptional, 0, 10, "s", "gravity: velocity ramps, not fitted (default 0.5)"),
    object("pid", kOptional, &kPid, "position controller gains (Eq. 4)"),
};
// accept_calibration: the kinds whose fit changes the sensor constants.
constexpr std::array<std::string_view, 2> kAcceptableKinds = {"accel_gain", "gravity"};
constexpr std::array kAcceptArgs = {
    choice("kind", kRequired, kAcceptableKinds, "which calibration to apply"),
    integer("repetitions", kOptional, 1, 10, "",
            "average this many of the latest good runs of that kind (default 3, as the thesis did)"),
};

// load_tiles: the prototyper's tiles (Eq. 19/20, and §5.3.1's torque
// waveforms). A curve is a cubic spline through knots; its unit is the
// term's: a coefficient (stiffness, damping, mass) or a torque.
constexpr std::array kSplineArgs = {
    number_list("x", kRequired, {2, 256}, {-1e4, 1e4}, "rad, s or rad/s",
                "knots, strictly increasing (θ for position tiles, t for time tiles, θ̇ for torque_of_velocity)"),
    number_list("y", kRequired, {2, 256}, {-1e3, 1e3}, "",
                "values at the knots, as many as x: N·m/rad (f_pos), N·m·s/rad (f_vel), kg·m² (f_acc, mass), "
                "N·m (torque, torque_of_velocity)"),
    boolean("periodic", kOptional, "the curve repeats (y's ends equal); default: natural cubic ends"),
};
constexpr ObjectSchema kSpline{kSplineArgs, {}};
constexpr std::array<std::string_view, 6> kPositionTileTerms = {"f_pos",  "f_vel",              "f_acc",
                                                                "torque", "torque_of_velocity", "mass"};
constexpr std::array kPositionTileGroups = {GroupRule{GroupRule::Kind::at_least_one, kPositionTileTerms}};
constexpr std::array kPositionTileArgs = {
    number("theta_min", kRequired, -1000, 1000, "rad", "the tile acts from this angle"),
    number("theta_max", kRequired, -1000, 1000, "rad", "up to this angle (more than theta_min)"),
    object("f_pos", kOptional, &kSpline, "stiffness over θ: τ += f_pos(θ)·θ"),
    object("f_vel", kOptional, &kSpline, "damping over θ: τ += f_vel(θ)·θ̇"),
    object("f_acc", kOptional, &kSpline, "mass over θ: τ += f_acc(θ)·θ̈"),
    object("torque", kOptional, &kSpline, "torque over θ (absolute): τ += torque(θ)"),
    object("torque_of_velocity", kOptional, &kSpline,
           "torque over θ̇: τ += torque_of_velocity(θ̇), straight along its end slopes beyond its knots"),
    object("mass", kOptional, &kSpline, "mass over θ (kg·m², ≥ 0), added to the virtual mass"),
};
constexpr ObjectSchema kPositionTile{kPositionTileArgs, kPositionTileGroups};
constexpr std::array<std::string_view, 4> kTimeTileTerms = {"f_pos", "f_vel", "f_acc", "torque"};
constexpr std::array kTimeTileGroups = {GroupRule{GroupRule::Kind::at_least_one, kTimeTileTerms}};
constexpr std::array kTimeTileArgs = {
    number("start", kOptional, 0, 3600, "s", "the tile acts from this long after loading (default 0); its curves run from 0 then"),
    number("duration", kRequired, 0.001, 3600, "s", "the tile acts for this long from its start"),
    boolean("loop", kOptional, "repeat every period (default false: once)"),
    number("period", kOptional, 0.001, 7200, "s", "with loop: repeat this often, at least start + duration (the default)"),
    object("f_pos", kOptional, &kSpline, "stiffness over t: τ += f_pos(t)·θ"),
    object("f_vel", kOptional, &kSpline, "damping over t: τ += f_vel(t)·θ̇"),
    object("f_acc", kOptional, &kSpline, "mass over t: τ += f_acc(t)·θ̈"),
    object("torque", kOptional, &kSpline, "torque over t: τ += torque(t)"),
};
constexpr ObjectSchema kTimeTile{kTimeTileArgs, kTimeTileGroups};
constexpr std::array kTilesArgs = {
    object_list("position", kOptional, {0, 16}, &kPositionTile, "position tiles (Eq. 19)"),
    object_list("time", kOptional, {0, 16}, &kTimeTile, "time tiles (Eq. 20), timed from when they load"),
};

constexpr std::array<std::string_view, 4> kModes = {"idle", "render", "capture", "calibrate"};
constexpr std::array kModeArgs = {choice("mode", kRequired, kModes, "daemon mode")};

// subscribe
constexpr std::array<std::string_view, kEventNames.size() + 1> kSubscribable = {
    kEventNames[0], kEventNames[1], kEventNames[2], kEventNames[3],
    kEventNames[4], kEventNames[5], kEventNames[6], kEventNames[7], "*"};
static_assert(kEventNames.size() == 8, "list every event in kSubscribable");
constexpr std::array kSubscribeArgs = {
    choice_list("events", kRequired, {0, kSubscribable.size()}, kSubscribable,
                "events to receive from now on (replaces the previous set; \"*\" = all)"),
    boolean("telemetry", kOptional, "also return the telemetry shared-memory name"),
};

constexpr std::array kTable = {
    CommandSpec{Command::hello, {kHelloArgs, {}}, "negotiate the version; optionally supervise",
                R"({"versions":[1],"client":"knoblab-cli"})"},
    CommandSpec{Command::ping, {}, "heartbeat (feeds the watchdog)", "{}"},
    CommandSpec{Command::get_state, {}, "the daemon's current state", "{}"},
    CommandSpec{Command::load_model, {kModelArgs, kModelGroups}, "replace the render model",
                R"({"M_acc":1.3e-05,"B_vel":0.0002,"A_pos":0.01,"P_pos":0.05})"},
    CommandSpec{Command::set_params, {kParamArgs, kParamGroups},
                "change some render-model parameters (slider drags)", R"({"B_vel":0.0005})"},
    CommandSpec{Command::start_capture, {kCaptureArgs, kCaptureGroups}, "start a capture",
                R"({"swept_sine":{"a":0,"b":1.5,"c":1,"d":3},"seconds":6,"knob":"demo"})"},
    CommandSpec{Command::stop_capture, {}, "stop the running capture", "{}"},
    CommandSpec{Command::start_trial, {kTrialArgs, {}}, "start a study trial",
                R"({"study":"S1","participant":7,"condition":"detents-12"})"},
    CommandSpec{Command::stop_trial, {}, "stop the running trial", "{}"},
    CommandSpec{Command::calibrate, {kCalibrateArgs, {}}, "run a calibration", R"({"kind":"spatial"})"},
    CommandSpec{Command::accept_calibration, {kAcceptArgs, {}},
                "apply the average of the latest calibration runs to the sensors", R"({"kind":"accel_gain"})"},
    CommandSpec{Command::load_tiles, {kTilesArgs, {}}, "render these prototyper tiles on top of the model ({} clears)",
                R"({"position":[{"theta_min":-3.1416,"theta_max":3.1416,"f_vel":{"x":[-3.1416,0,3.1416],"y":[0.0005,0.002,0.0005]}}]})"},
    CommandSpec{Command::clear_fault, {}, "clear a latched fault", "{}"},
    CommandSpec{Command::set_mode, {kModeArgs, {}}, "switch the daemon's mode", R"({"mode":"render"})"},
    CommandSpec{Command::subscribe, {kSubscribeArgs, {}}, "choose the events pushed to this client",
                R"({"events":["state","fault_latched"],"telemetry":true})"},
};
static_assert(kTable.size() == kCommandCount);

constexpr bool table_in_enum_order() {
  for (std::size_t i = 0; i < kTable.size(); ++i)
    if (static_cast<std::size_t>(kTable[i].command) != i) return false;
  return true;
}
static_assert(table_in_enum_order(), "kTable rows must follow the Command enum");

}  // namespace

std::span<const CommandSpec> command_table() noexcept { return kTable; }

const CommandSpec& command_spec(Command command) noexcept {
  return kTable[static_cast<std::size_t>(command)];
}

}  // namespace knoblab::control
