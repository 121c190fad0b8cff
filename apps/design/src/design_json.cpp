#include "knoblab/design/design_json.hpp"

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "knoblab/design/curve.hpp"
#include "knoblab/jsonread/nesting.hpp"

namespace knoblab::design {

namespace {

using jsonread::ObjectReader;
using jsonread::PathError;
using nlohmann::json;

const std::vector<std::string_view>& channel_names() {
  static const std::vector<std::string_view> names{"position", "velocity", "acceleration", "time"};
  return names;
}

json tile_json(const Tile& t) {
  return {{"name", t.name}, {"drawn_for", channel_name(t.drawn_for)}, {"waveform", waveform_json(t.waveform)}};
}

Channel read_channel(const json& v, const std::string& path) {
  return static_cast<Channel>(jsonread::as_choice(v, path, channel_names()));
}

Tile read_tile(const json& v, const std::string& path) {
  ObjectReader r(v, path);
  Tile t;
  t.name = r.string("name");
  if (const json* c = r.find("drawn_for")) t.drawn_for = read_channel(*c, r.path_of("drawn_for"));
  t.waveform = read_waveform(r.require("waveform"), r.path_of("waveform"));
  r.finish();
  return t;
}

PlacedTile read_placed(const json& v, const std::string& path, Channel c) {
  ObjectReader r(v, path);
  PlacedTile p;
  p.from = r.number("from");
  p.to = r.number("to");
  if (!(p.to > p.from)) jsonread::fail(r.path_of("to"), "must be more than from (" + std::to_string(p.from) + ")");
  if (c == Channel::Time && p.from < 0.0) jsonread::fail(r.path_of("from"), "a time tile starts at 0 s or later");
  p.tile = read_tile(r.require("tile"), r.path_of("tile"));
  r.finish();
  return p;
}

ChannelLines read_channel_lines(const json& v, const std::string& path, Channel c) {
  ObjectReader r(v, path);
  ChannelLines cl;
  cl.play = r.boolean_or("play", true);
  if (const json* lines = r.find("lines")) {
    jsonread::check_array(*lines, r.path_of("lines"), 0);
    for (std::size_t i = 0; i < lines->size(); ++i) {
      const std::string lp = jsonread::element_path(r.path_of("lines"), i);
      ObjectReader lr((*lines)[i], lp);
      Line line;
      line.active = lr.boolean_or("active", true);
      if (const json* tiles = lr.find("tiles")) {
        jsonread::check_array(*tiles, lr.path_of("tiles"), 0);
        for (std::size_t k = 0; k < tiles->size(); ++k)
          line.tiles.push_back(read_placed((*tiles)[k], jsonread::element_path(lr.path_of("tiles"), k), c));
      }
      lr.finish();
      cl.lines.push_back(std::move(line));
    }
  }
  r.finish();
  return cl;
}

}  // namespace

json waveform_json(const Waveform& w) {
  json x = json::array(), y = json::array();
  for (const Point& p : w.points) {
    x.push_back(p.x);
    y.push_back(p.y);
  }
  json j{{"x", x}, {"y", y}};
  if (w.periodic) j["periodic"] = true;
  return j;
}

Waveform read_waveform(const json& v, const std::string& path, const std::string& noun) {
  ObjectReader r(v, path);
  const json& xs = r.require("x");
  const json& ys = r.require("y");
  jsonread::check_array(xs, r.path_of("x"), 2);
  jsonread::check_array(ys, r.path_of("y"), 2);
  if (xs.size() != ys.size())
    jsonread::fail(r.path_of("y"), "has " + std::to_string(ys.size()) + " values but x has " +
                                       std::to_string(xs.size()) + "; give one y per x");
  Waveform w;
  for (std::size_t i = 0; i < xs.size(); ++i)
    w.points.push_back({jsonread::as_number(xs[i], jsonread::element_path(r.path_of("x"), i)),
                        jsonread::as_number(ys[i], jsonread::element_path(r.path_of("y"), i))});
  w.periodic = r.boolean_or("periodic", false);
  r.finish();
  if (const std::string why = waveform_problem(w); !why.empty()) jsonread::fail(path, noun + " " + why);
  return w;
}

json to_json(const Design& d) {
  json j{{"format", kDesignFormat}, {"version", kDesignVersion}, {"name", d.name}};
  if (!d.editor.waveform.points.empty())
    j["editor"] = {{"drawn_for", channel_name(d.editor.drawn_for)}, {"waveform", waveform_json(d.editor.waveform)}};
  json palette = json::array();
  for (const PaletteTab& tab : d.palette) {
    json tiles = json::array();
    for (const Tile& t : tab.tiles) tiles.push_back(tile_json(t));
    palette.push_back({{"tab", tab.name}, {"tiles", tiles}});
  }
  j["palette"] = palette;
  json channels = json::object();
  for (const Channel c : kChannels) {
    json lines = json::array();
    for (const Line& line : d.lines(c).lines) {
      json tiles = json::array();
      for (const PlacedTile& p : line.tiles) tiles.push_back({{"from", p.from}, {"to", p.to}, {"tile", tile_json(p.tile)}});
      lines.push_back({{"active", line.active}, {"tiles", tiles}});
    }
    channels[std::string(channel_name(c))] = {{"play", d.lines(c).play}, {"lines", lines}};
  }
  j["channels"] = channels;
  j["time_loop"] = d.time_loop;
  return j;
}

Design design_from_json(const json& j) {
  ObjectReader r(j, "", "design");
  const std::string format = r.string("format");
  if (format != kDesignFormat)
    jsonread::fail(r.path_of("format"), "is \"" + format + "\"; a design file says \"" + kDesignFormat + "\"");
  const json& version = r.require("version");
  if (!version.is_number_integer() || version.get<long long>() != kDesignVersion)
    jsonread::fail(r.path_of("version"), "this knoblab reads version " + std::to_string(kDesignVersion) + ", got " +
                                             version.dump());
  Design d;
  d.name = r.string("name");
  if (const json* e = r.find("editor")) {
    ObjectReader er(*e, r.path_of("editor"));
    if (const json* c = er.find("drawn_for")) d.editor.drawn_for = read_channel(*c, er.path_of("drawn_for"));
    d.editor.waveform = read_waveform(er.require("waveform"), er.path_of("waveform"));
    er.finish();
  }
  if (const json* palette = r.find("palette")) {
    jsonread::check_array(*palette, r.path_of("palette"), 0);
    for (std::size_t i = 0; i < palette->size(); ++i) {
      const std::string tp = jsonread::element_path(r.path_of("palette"), i);
      ObjectReader tr((*palette)[i], tp);
      PaletteTab tab;
      tab.name = tr.string("tab");
      if (const json* tiles = tr.find("tiles")) {
        jsonread::check_array(*tiles, tr.path_of("tiles"), 0);
        for (std::size_t k = 0; k < tiles->size(); ++k)
          tab.tiles.push_back(read_tile((*tiles)[k], jsonread::element_path(tr.path_of("tiles"), k)));
      }
      tr.finish();
      d.palette.push_back(std::move(tab));
    }
  }
  if (const json* channels = r.find("channels")) {
    ObjectReader cr(*channels, r.path_of("channels"));
    for (const Channel c : kChannels)
      if (const json* v = cr.find(channel_name(c))) d.lines(c) = read_channel_lines(*v, cr.path_of(channel_name(c)), c);
    cr.finish();
  }
  d.time_loop = r.boolean_or("time_loop", false);
  r.finish();
  return d;
}

Design read_design(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw PathError("", "cannot read " + file.string());
  try {
    std::ostringstream text;
    text << in.rdbuf();
    if (const auto deep = jsonread::nesting_problem(text.view())) throw PathError("", "not JSON we read: " + *deep);
    json j;
    try {
      j = json::parse(text.view());
    } catch (const json::parse_error& e) {
      throw PathError("", std::string("not JSON: ") + e.what());
    }
    return design_from_json(j);
  } catch (const PathError& e) {
    throw e.in_file(file.string());
  }
}

void write_design(const std::filesystem::path& file, const Design& d) {
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out << to_json(d).dump(2) << '\n';
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw std::runtime_error("cannot replace " + file.string() + ": " + ec.message());
  }
}

}  // namespace knoblab::design
