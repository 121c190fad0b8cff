#include "design_render.hpp"

#include <algorithm>
#include <cmath>
#include <format>
#include <numbers>
#include <memory>
#include <variant>

#include "knoblab/design/render_tiles.hpp"
#include "knoblab/hapticd/core.hpp"
#include "knoblab/hapticd/render_controller.hpp"
#include "knoblab/hapticd/sim_time_loop.hpp"
#include "knoblab/hapticd/supervisor.hpp"
#include "knoblab/hapticd/tiles_json.hpp"
#include "knoblab/sim/guided_hand.hpp"
#include "knoblab/sim/presets.hpp"
#include "knoblab/version.hpp"

namespace knoblab::cli {

namespace {

// The sweep: from rest at 0 to one end, across to the other, back, and home,
// as fractions of the whole time: slow enough that the hand feels every detent.
struct Leg {
  double share;  // of the request's seconds
  int to;        // -1: the range's start, +1: its end, 0: where it began
};
constexpr Leg kSweep[] = {{0.15, -1}, {0.35, +1}, {0.35, -1}, {0.15, 0}};

// The design as hapticd takes it at this loop rate: the same checks, the
// same stable region.
std::variant<std::unique_ptr<hapticd::TileSet>, hapticd::ParamProblem> tile_set(const design::Design& d,
                                                                                double rate_hz) {
  return hapticd::tiles_from_json(design::load_tiles_args(d), hapticd::SafetyLimits{},
                                  hapticd::RenderController::loop_dynamics(rate_hz));
}

// Where the design acts: from the first tile's start to the last tile's end
// over the channels laid out along θ.
std::pair<double, double> range_of(const design::Design& d) {
  double lo = INFINITY, hi = -INFINITY;
  for (const design::Channel c : design::kChannels) {
    if (c == design::Channel::Time) continue;
    for (const design::Line& line : d.lines(c).lines)
      for (const design::PlacedTile& p : line.tiles) {
        lo = std::min(lo, p.from);
        hi = std::max(hi, p.to);
      }
  }
  if (!(hi > lo)) return {-1.0, 1.0};  // only time tiles: turn a little either way
  return {lo, hi};
}

}  // namespace

std::string design_render_refusal(const design::Design& d, double rate_hz) {
  auto parsed = tile_set(d, rate_hz);
  if (const auto* problem = std::get_if<hapticd::ParamProblem>(&parsed)) return problem->message;
  return {};
}

DesignRenderResult render_design(const DesignRenderRequest& r) {
  if (!(r.seconds > 0.5 && r.seconds <= 600)) throw std::invalid_argument("--seconds must be more than 0.5 and at most 600");
  if (!(r.rate_hz >= 1000 && r.rate_hz <= 100000)) throw std::invalid_argument("--rate must be 1000 to 100000 Hz");
  const sim::presets::Preset* preset = sim::presets::find(r.knob);
  if (!preset) throw std::invalid_argument("no sim knob preset '" + r.knob + "' (knoblab simulate --list)");
  auto parsed = tile_set(r.design, r.rate_hz);
  if (const auto* problem = std::get_if<hapticd::ParamProblem>(&parsed))
    throw std::invalid_argument("hapticd would refuse this design: " + problem->message);

  sim::PlantConfig plant;
  plant.knob = preset->knob;
  hapticd::SimTimeLoop loop(plant, r.rate_hz);
  sim::HandChannel hand;
  loop.daq().plant().add_effect(sim::make_guided_hand(hand));
  if (!loop.core().load_tiles(std::move(std::get<std::unique_ptr<hapticd::TileSet>>(parsed))))
    throw std::runtime_error("hapticd's core did not take the tiles");
  hapticd::CoreCommand mode;
  mode.kind = hapticd::CoreCommand::SetMode;
  mode.mode = hapticd::Mode::Render;
  if (!loop.post(mode)) throw std::runtime_error("hapticd's core did not take render mode");

  DesignRenderResult out;
  std::tie(out.range_from, out.range_to) = range_of(r.design);
  const long cycles = std::lround(r.seconds * r.rate_hz);
  interchange::Capture& c = out.capture;
  for (auto* v : {&c.t, &c.theta, &c.omega, &c.alpha, &c.torque, &c.command}) v->reserve(static_cast<std::size_t>(cycles));
  c.flags.reserve(static_cast<std::size_t>(cycles));
  c.has_command = true;

  hand.send({0.0, 0.0, r.grip_stiffness, r.grip_damping});
  double leg_start = 0.0;
  std::size_t leg = 0;
  bool leg_sent = false;
  for (long i = 0; i < cycles; ++i) {
    const double t = static_cast<double>(i) / r.rate_hz;
    if (leg < std::size(kSweep) && !leg_sent) {
      const Leg& l = kSweep[leg];
      const double to = l.to < 0 ? out.range_from : l.to > 0 ? out.range_to : 0.0;
      hand.send({to, l.share * r.seconds, r.grip_stiffness, r.grip_damping});
      leg_sent = true;
    }
    if (leg < std::size(kSweep) && t >= leg_start + kSweep[leg].share * r.seconds) {
      leg_start += kSweep[leg].share * r.seconds;
      ++leg;
      leg_sent = false;
    }
    const hapticd::LoopRecord& rec = loop.step();
    if (rec.faults != 0)
      throw std::runtime_error(std::format("hapticd's core latched a fault ({}) at t = {:.3f} s, θ = {:.1f}°",
                                           hapticd::fault_list(rec.faults), t, rec.sample.theta * 180.0 / std::numbers::pi));
    c.t.push_back(t);
    c.theta.push_back(rec.sample.theta);
    c.omega.push_back(rec.sample.omega);
    c.alpha.push_back(rec.sample.alpha);
    c.torque.push_back(r.torque == RenderedTorque::Knob ? -rec.sample.torque : rec.sample.torque);
    c.command.push_back(rec.sample.command);
    c.flags.push_back(rec.sample.flags);
  }
  c.metadata = {{"source", "knoblab design render"},
                {"knoblab_version", kVersion},
                {"design", r.design.name},
                {"knob", r.knob},
                {"rate_hz", std::format("{}", r.rate_hz)},
                {"torque", r.torque == RenderedTorque::Knob
                               ? "knob: the torque it takes to turn the knob, the torque sensor's reading negated"
                               : "sensor: the torque sensor's reading, the motor's push on the knob"},
                {"hand", std::format("turned across {:.4g}…{:.4g} rad and back in {} s, grip {} N·m/rad, {} N·m·s/rad",
                                     out.range_from, out.range_to, r.seconds, r.grip_stiffness, r.grip_damping)}};
  return out;
}

}  // namespace knoblab::cli
