#include "knoblab/design/edits.hpp"

#include <algorithm>
#include <cmath>
#include <format>
#include <iterator>
#include <vector>

#include "knoblab/design/curve.hpp"

namespace knoblab::design {

namespace {

// Two control points closer than this in x are one point.
constexpr double kMinGap = 1e-9;
// The sum of two tiles is sampled at both tiles' points and this many more
// between each pair, so the sum's spline follows both curves.
constexpr int kSuperimposeSubdivisions = 4;

[[noreturn]] void refuse(const std::string& why) { throw EditError(why); }

std::string unit_text(double v, std::string_view unit) { return std::format("{:.4g} {}", v, unit); }

void check_name(const std::string& name, const char* what) {
  if (name.empty()) refuse(std::format("A {} needs a name.", what));
}

// The curve must stay a function the renderer can play.
void check_waveform(const Waveform& w, const char* what) {
  if (const std::string why = waveform_problem(w); !why.empty()) refuse(std::format("{} {}.", what, why));
}

Waveform& editor_waveform(Design& d) {
  if (d.editor.waveform.points.empty()) refuse("The editor is empty: drag a tile or a template into it first.");
  return d.editor.waveform;
}

std::size_t check_point(const Design& d, std::size_t i) {
  if (i >= d.editor.waveform.points.size()) refuse(std::format("There is no point {} in the editor.", i + 1));
  return i;
}

PaletteTab& tab_at(Design& d, std::size_t tab) {
  if (tab >= d.palette.size()) refuse(std::format("There is no palette tab {}.", tab + 1));
  return d.palette[tab];
}

Tile& tile_at(Design& d, std::size_t tab, std::size_t index) {
  PaletteTab& t = tab_at(d, tab);
  if (index >= t.tiles.size()) refuse(std::format("Tab \"{}\" has no tile {}.", t.name, index + 1));
  return t.tiles[index];
}

Line& line_at(Design& d, Channel c, std::size_t line) {
  ChannelLines& lines = d.lines(c);
  if (line >= lines.lines.size()) refuse(std::format("The {} channel has no line {}.", channel_name(c), line + 1));
  return lines.lines[line];
}

PlacedTile& placed_at(Design& d, TileRef r) {
  Line& line = line_at(d, r.channel, r.line);
  if (r.index >= line.tiles.size())
    refuse(std::format("Line {} of the {} channel has no tile {}.", r.line + 1, channel_name(r.channel), r.index + 1));
  return line.tiles[r.index];
}

void check_span(Channel c, double from, double to) {
  const std::string_view unit = c == Channel::Time ? "s" : "rad";  // where tiles lie, whatever their waveform
  if (!std::isfinite(from) || !std::isfinite(to) || !(to - from > kMinGap))
    refuse(std::format("A tile must end after it starts ({} to {}).", unit_text(from, unit), unit_text(to, unit)));
  if (c == Channel::Time && from < 0.0) refuse("Time tiles start at 0 s or later.");
}

// Keeps a line's tiles in order of where they start, so the pane draws and
// the renderer sums them in a stable order.
void sort_line(Line& line) {
  std::stable_sort(line.tiles.begin(), line.tiles.end(),
                   [](const PlacedTile& a, const PlacedTile& b) { return a.from < b.from; });
}

// A placed tile's value in its channel's coordinates at s (0 outside the
// span of a stretched tile; velocity tiles are evaluated at a velocity).
struct PlacedCurve {
  Waveform w;
  model::CubicSpline spline;
  bool bounded;
  double operator()(double s) const {
    if (bounded && (s < w.x_min() || s > w.x_max())) return 0.0;
    return value_at(spline, s);
  }
};

PlacedCurve curve_of(const PlacedTile& p, Channel c) {
  Waveform w = placed_waveform(p, c);
  model::CubicSpline s = spline_of(w);
  return {std::move(w), std::move(s), stretched(c)};
}

}  // namespace

void set_editor(Design& d, const Waveform& w, Channel drawn_for) {
  check_waveform(w, "The waveform");
  d.editor.waveform = w;
  d.editor.drawn_for = drawn_for;
}

void move_point(Design& d, std::size_t i, Point to) {
  Waveform& w = editor_waveform(d);
  check_point(d, i);
  if (!std::isfinite(to.x) || !std::isfinite(to.y)) refuse("A point's angle and torque must be numbers.");
  // A dragged point stops at its neighbours rather than jumping past them.
  if (i > 0) to.x = std::max(to.x, w.points[i - 1].x + 1e-6 * std::max(1.0, std::abs(w.points[i - 1].x)));
  if (i + 1 < w.points.size())
    to.x = std::min(to.x, w.points[i + 1].x - 1e-6 * std::max(1.0, std::abs(w.points[i + 1].x)));
  if (i > 0 && !(to.x > w.points[i - 1].x)) refuse("There is no room for this point between its neighbours.");
  w.points[i] = to;
  // A repeating curve keeps its ends equal.
  if (w.periodic && (i == 0 || i + 1 == w.points.size())) w.points.front().y = w.points.back().y = to.y;
}

void add_point(Design& d, Point p) {
  Waveform& w = editor_waveform(d);
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) refuse("A point's angle and torque must be numbers.");
  const auto at = std::lower_bound(w.points.begin(), w.points.end(), p.x,
                                   [](const Point& q, double x) { return q.x < x; });
  if (at != w.points.end() && std::abs(at->x - p.x) <= kMinGap) refuse("There is already a point there.");
  w.points.insert(at, p);
}

void remove_point(Design& d, std::size_t i) {
  Waveform& w = editor_waveform(d);
  check_point(d, i);
  if (w.points.size() <= 2) refuse("A waveform keeps at least 2 points.");
  if (w.periodic && (i == 0 || i + 1 == w.points.size())) refuse("The ends of a repeating waveform stay.");
  w.points.erase(w.points.begin() + static_cast<std::ptrdiff_t>(i));
}

void scale_selection(Design& d, Selection s, Mirror m, double at, double factor) {
  Waveform& w = editor_waveform(d);
  if (!std::isfinite(factor) || factor == 0.0) refuse("Scale by a number other than 0.");
  if (!std::isfinite(at)) refuse("The mirror line must be at a number.");
  // The selected points are a run of neighbours (the points are in x order).
  std::size_t first = w.points.size(), last = 0;
  for (std::size_t i = 0; i < w.points.size(); ++i)
    if (w.points[i].x >= s.from && w.points[i].x <= s.to) {
      first = std::min(first, i);
      last = i;
    }
  if (first == w.points.size()) refuse("No points are selected: drag across the waveform first.");
  Waveform next = w;
  const auto begin = next.points.begin() + static_cast<std::ptrdiff_t>(first);
  const auto end = next.points.begin() + static_cast<std::ptrdiff_t>(last + 1);
  for (auto p = begin; p != end; ++p) {
    if (m == Mirror::Horizontal) p->y = at + factor * (p->y - at);
    else p->x = at + factor * (p->x - at);
  }
  if (m == Mirror::Vertical) {
    if (factor < 0.0) std::reverse(begin, end);  // mirrored: the run reads right to left
    // The run must stay between the points beside it, or the curve would
    // be another curve, not a stretched one.
    bool fits = true;
    for (std::size_t i = 1; i < next.points.size(); ++i) fits = fits && next.points[i].x - next.points[i - 1].x > kMinGap;
    if (!fits) refuse("Stretched so, the selection would overlap the points beside it: select more, or scale less.");
  }
  if (next.periodic) next.periodic = next.points.front().y == next.points.back().y;
  w = std::move(next);
}

Tile tile_from_selection(const Design& d, Selection s, const std::string& name) {
  check_name(name, "tile");
  const Waveform& w = d.editor.waveform;
  if (w.points.size() < 2) refuse("The editor is empty: drag a tile or a template into it first.");
  const double from = std::max(s.from, w.x_min()), to = std::min(s.to, w.x_max());
  if (!(to - from > kMinGap)) refuse("Select a stretch of the waveform first.");
  const model::CubicSpline curve = spline_of(w);
  Tile t{name, {}, d.editor.drawn_for};
  t.waveform.points.push_back({from, value_at(curve, from)});
  for (const Point& p : w.points)
    if (p.x - from > kMinGap && to - p.x > kMinGap) t.waveform.points.push_back(p);
  t.waveform.points.push_back({to, value_at(curve, to)});
  return t;
}

void add_tab(Design& d, const std::string& name) {
  check_name(name, "tab");
  d.palette.push_back({name, {}});
}

void rename_tab(Design& d, std::size_t tab, const std::string& name) {
  check_name(name, "tab");
  tab_at(d, tab).name = name;
}

void remove_tab(Design& d, std::size_t tab) {
  tab_at(d, tab);
  d.palette.erase(d.palette.begin() + static_cast<std::ptrdiff_t>(tab));
}

void add_tile(Design& d, std::size_t tab, const Tile& t) {
  check_name(t.name, "tile");
  check_waveform(t.waveform, "The tile");
  tab_at(d, tab).tiles.push_back(t);
}

void rename_tile(Design& d, std::size_t tab, std::size_t index, const std::string& name) {
  check_name(name, "tile");
  tile_at(d, tab, index).name = name;
}

void remove_tile(Design& d, std::size_t tab, std::size_t index) {
  tile_at(d, tab, index);
  auto& tiles = d.palette[tab].tiles;
  tiles.erase(tiles.begin() + static_cast<std::ptrdiff_t>(index));
}

void edit_tile(Design& d, std::size_t tab, std::size_t index) {
  const Tile& t = tile_at(d, tab, index);
  set_editor(d, t.waveform, t.drawn_for);
}

void place_tile(Design& d, Channel c, std::size_t line, const Tile& t, double from, double to) {
  check_waveform(t.waveform, "The tile");
  check_span(c, from, to);
  ChannelLines& lines = d.lines(c);
  if (line > lines.lines.size())
    refuse(std::format("The {} channel has {} lines; place on one of them or start a new one.", channel_name(c),
                       lines.lines.size()));
  if (line == lines.lines.size()) lines.lines.emplace_back();
  lines.lines[line].tiles.push_back({t, from, to});
  sort_line(lines.lines[line]);
}

void move_tile(Design& d, TileRef r, double from) {
  PlacedTile& p = placed_at(d, r);
  const double length = p.to - p.from;
  check_span(r.channel, from, from + length);
  p.from = from;
  p.to = from + length;
  sort_line(line_at(d, r.channel, r.line));
}

void resize_tile(Design& d, TileRef r, double from, double to) {
  PlacedTile& p = placed_at(d, r);
  check_span(r.channel, from, to);
  p.from = from;
  p.to = to;
  sort_line(line_at(d, r.channel, r.line));
}

void remove_placed(Design& d, TileRef r) {
  placed_at(d, r);
  auto& tiles = d.lines(r.channel).lines[r.line].tiles;
  tiles.erase(tiles.begin() + static_cast<std::ptrdiff_t>(r.index));
}

void superimpose(Design& d, TileRef a, TileRef b) {
  if (a.channel != b.channel) refuse("Only tiles of one channel add up: both must be in the same channel.");
  if (a == b) refuse("Pick two different tiles to superimpose.");
  const Channel c = a.channel;
  const PlacedTile pa = placed_at(d, a), pb = placed_at(d, b);
  if (!stretched(c) && (pa.from != pb.from || pa.to != pb.to))
    refuse("Velocity tiles add up only over the same span of angles: give both the same span first.");
  const PlacedCurve ca = curve_of(pa, c), cb = curve_of(pb, c);

  // Where the sum is sampled: both tiles' points, and points between them.
  std::vector<double> knots;
  for (const Point& p : ca.w.points) knots.push_back(p.x);
  for (const Point& p : cb.w.points) knots.push_back(p.x);
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end(), [](double u, double v) { return v - u <= kMinGap; }),
              knots.end());
  std::vector<double> at;
  for (std::size_t i = 0; i + 1 < knots.size(); ++i)
    for (int k = 0; k < kSuperimposeSubdivisions; ++k)
      at.push_back(knots[i] + (knots[i + 1] - knots[i]) * k / kSuperimposeSubdivisions);
  at.push_back(knots.back());

  PlacedTile sum;
  sum.tile.name = pa.tile.name + " + " + pb.tile.name;
  sum.tile.drawn_for = pa.tile.drawn_for;
  for (const double s : at) sum.tile.waveform.points.push_back({s, ca(s) + cb(s)});
  sum.from = stretched(c) ? at.front() : pa.from;
  sum.to = stretched(c) ? at.back() : pa.to;

  // b goes first, so a's index stays valid when both share a line.
  Line& line_b = line_at(d, c, b.line);
  line_b.tiles.erase(line_b.tiles.begin() + static_cast<std::ptrdiff_t>(b.index));
  Line& line_a = line_at(d, c, a.line);
  const std::size_t ia = (a.line == b.line && b.index < a.index) ? a.index - 1 : a.index;
  line_a.tiles[ia] = std::move(sum);
  sort_line(line_a);
}

void add_line(Design& d, Channel c) { d.lines(c).lines.emplace_back(); }

void remove_line(Design& d, Channel c, std::size_t line) {
  line_at(d, c, line);
  auto& lines = d.lines(c).lines;
  lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(line));
}

void set_line_active(Design& d, Channel c, std::size_t line, bool active) { line_at(d, c, line).active = active; }

void set_channel_play(Design& d, Channel c, bool play) { d.lines(c).play = play; }

void set_time_loop(Design& d, bool loop) { d.time_loop = loop; }

void rename_design(Design& d, const std::string& name) {
  check_name(name, "design");
  d.name = name;
}

}  // namespace knoblab::design
