#include "pane_snap.hpp"

#include <cmath>

namespace knoblab::ui {

namespace {

bool shares_axis(design::Channel a, design::Channel b) {
  return (a == design::Channel::Time) == (b == design::Channel::Time);
}

// The edge nearest `at` within `tolerance`, if any.
std::optional<double> nearest(double at, const std::vector<double>& edges, double tolerance) {
  std::optional<double> best;
  for (const double e : edges)
    if (std::abs(e - at) <= tolerance && (!best || std::abs(e - at) < std::abs(*best - at))) best = e;
  return best;
}

}  // namespace

PaneSpan snap_span(double from, double length, const std::vector<double>& edges, double tolerance) {
  const std::optional<double> start = nearest(from, edges, tolerance);
  const std::optional<double> end = nearest(from + length, edges, tolerance);
  // Each end is assigned the edge itself, so it equals it bit for bit.
  if (start && (!end || std::abs(*start - from) <= std::abs(*end - (from + length))))
    return {*start, *start + length};
  if (end) return {*end - length, *end};
  return {from, from + length};
}

double snap_edge(double at, const std::vector<double>& edges, double tolerance) {
  return nearest(at, edges, tolerance).value_or(at);
}

PaneSpan fill_gap(double at, const std::vector<double>& edges, double fallback) {
  std::optional<double> left, right;
  for (const double e : edges) {
    if (e <= at && (!left || e > *left)) left = e;
    if (e > at && (!right || e < *right)) right = e;
  }
  return {left.value_or(at - fallback / 2), right.value_or(at + fallback / 2)};
}

std::vector<double> pane_edges(const design::Design& d, design::Channel c,
                               std::optional<std::pair<std::size_t, std::size_t>> skip) {
  std::vector<double> edges;
  for (const design::Channel other : design::kChannels) {
    if (!shares_axis(c, other)) continue;
    const auto& lines = d.lines(other).lines;
    for (std::size_t l = 0; l < lines.size(); ++l)
      for (std::size_t i = 0; i < lines[l].tiles.size(); ++i) {
        if (other == c && skip && skip->first == l && skip->second == i) continue;
        edges.push_back(lines[l].tiles[i].from);
        edges.push_back(lines[l].tiles[i].to);
      }
  }
  return edges;
}

}  // namespace knoblab::ui
