#include "knoblab/design/render_tiles.hpp"

#include <algorithm>
#include <vector>

#include "knoblab/design/curve.hpp"
#include "knoblab/design/design_json.hpp"
#include "knoblab/jsonread/json_reader.hpp"

namespace knoblab::design {

namespace {

using jsonread::ObjectReader;
using nlohmann::json;

const char* position_key(Channel c) {
  switch (c) {
    case Channel::Velocity: return "torque_of_velocity";
    case Channel::Acceleration: return "mass";
    default: return "torque";
  }
}

}  // namespace

double time_channel_end(const Design& d) {
  double end = 0.0;
  for (const Line& line : d.lines(Channel::Time).lines)
    for (const PlacedTile& p : line.tiles) end = std::max(end, p.to);
  return end;
}

json load_tiles_args(const Design& d) {
  json position = json::array(), time = json::array();
  const double time_end = time_channel_end(d);
  for (const Channel c : kChannels) {
    const ChannelLines& cl = d.lines(c);
    if (!cl.play) continue;
    for (const Line& line : cl.lines) {
      if (!line.active) continue;
      for (const PlacedTile& p : line.tiles) {
        const Waveform w = placed_waveform(p, c);
        if (c == Channel::Time) {
          // Time tiles' curves run on their own clock, from 0 at `start`.
          Waveform local = w;
          for (Point& q : local.points) q.x -= p.from;
          json t{{"start", p.from}, {"duration", p.to - p.from}, {"torque", waveform_json(local)}};
          if (d.time_loop) {
            t["loop"] = true;
            t["period"] = time_end;
          }
          time.push_back(t);
        } else {
          position.push_back({{"theta_min", p.from}, {"theta_max", p.to}, {position_key(c), waveform_json(w)}});
        }
      }
    }
  }
  json args = json::object();
  if (!position.empty()) args["position"] = position;
  if (!time.empty()) args["time"] = time;
  return args;
}

Design design_from_load_tiles(const json& args, const std::string& name) {
  Design d;
  d.name = name;
  ObjectReader r(args, "", "render model");
  auto tile_named = [](Channel c, std::size_t i, Waveform w) {
    return Tile{std::string(channel_name(c)) + " " + std::to_string(i + 1), std::move(w), c};
  };
  if (const json* list = r.find("position")) {
    jsonread::check_array(*list, r.path_of("position"), 0);
    for (std::size_t i = 0; i < list->size(); ++i) {
      const std::string path = jsonread::element_path(r.path_of("position"), i);
      ObjectReader t((*list)[i], path);
      const double from = t.number("theta_min"), to = t.number("theta_max");
      if (!(to > from)) jsonread::fail(t.path_of("theta_max"), "must be more than theta_min");
      bool any = false;
      for (const Channel c : {Channel::Position, Channel::Velocity, Channel::Acceleration})
        if (const json* v = t.find(position_key(c))) {
          ChannelLines& cl = d.lines(c);
          if (cl.lines.empty()) cl.lines.emplace_back();
          cl.lines[0].tiles.push_back({tile_named(c, cl.lines[0].tiles.size(), read_waveform(*v, t.path_of(position_key(c)), "the curve")), from, to});
          any = true;
        }
      if (!any) jsonread::fail(path, "has none of torque, torque_of_velocity, mass (the prototyper's curves)");
      t.finish();
    }
  }
  if (const json* list = r.find("time")) {
    jsonread::check_array(*list, r.path_of("time"), 0);
    for (std::size_t i = 0; i < list->size(); ++i) {
      ObjectReader t((*list)[i], jsonread::element_path(r.path_of("time"), i));
      const double start = t.find("start") ? t.number("start") : 0.0;
      const double duration = t.number("duration");
      Waveform w = read_waveform(t.require("torque"), t.path_of("torque"), "the curve");
      for (Point& q : w.points) q.x += start;
      if (t.boolean_or("loop", false)) d.time_loop = true;
      if (t.find("period")) t.number("period");  // the channel's length, which the tiles give again
      ChannelLines& cl = d.lines(Channel::Time);
      if (cl.lines.empty()) cl.lines.emplace_back();
      cl.lines[0].tiles.push_back({tile_named(Channel::Time, cl.lines[0].tiles.size(), std::move(w)), start, start + duration});
      t.finish();
    }
  }
  r.finish();
  return d;
}

}  // namespace knoblab::design
