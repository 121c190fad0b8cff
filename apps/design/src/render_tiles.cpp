#include "knoblab/design/render_tiles.hpp"

#include <algorithm>
#include <vector>

#include "knoblab/design/curve.hpp"
#include "knoblab/jsonread/json_reader.hpp"

namespace knoblab::design {

namespace {

using jsonread::ObjectReader;
using nlohmann::json;

json curve_json(const Waveform& w) {
  json x = json::array(), y = json::array();
  for (const Point& p : w.points) {
    x.push_back(p.x);
    y.push_back(p.y);
  }
  json j{{"x", x}, {"y", y}};
  if (w.periodic) j["periodic"] = true;
  return j;
}

const char* position_key(Channel c) {
  switch (c) {
    case Channel::Velocity: return "torque_of_velocity";
    case Channel::Acceleration: return "mass";
    default: return "torque";
  }
}

Waveform read_curve(const json& v, const std::string& path) {
  ObjectReader r(v, path);
  const json& xs = r.require("x");
  const json& ys = r.require("y");
  jsonread::check_array(xs, r.path_of("x"), 2);
  jsonread::check_array(ys, r.path_of("y"), 2);
  if (xs.size() != ys.size()) jsonread::fail(r.path_of("y"), "needs as many values as x");
  Waveform w;
  for (std::size_t i = 0; i < xs.size(); ++i)
    w.points.push_back({jsonread::as_number(xs[i], jsonread::element_path(r.path_of("x"), i)),
                        jsonread::as_number(ys[i], jsonread::element_path(r.path_of("y"), i))});
  w.periodic = r.boolean_or("periodic", false);
  r.finish();
  if (const std::string why = waveform_problem(w); !why.empty()) jsonread::fail(path, "the curve " + why);
  return w;
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
          json t{{"start", p.from}, {"duration", p.to - p.from}, {"torque", curve_json(local)}};
          if (d.time_loop) {
            t["loop"] = true;
            t["period"] = time_channel_end(d);
          }
          time.push_back(t);
        } else {
          position.push_back({{"theta_min", p.from}, {"theta_max", p.to}, {position_key(c), curve_json(w)}});
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
          cl.lines[0].tiles.push_back({tile_named(c, cl.lines[0].tiles.size(), read_curve(*v, t.path_of(position_key(c)))), from, to});
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
      Waveform w = read_curve(t.require("torque"), t.path_of("torque"));
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
