#include "figure_data.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

namespace knoblab::ui {

namespace {

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t at = 0;;) {
    const auto comma = line.find(',', at);
    out.push_back(line.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at));
    if (comma == std::string_view::npos) return out;
    at = comma + 1;
  }
}

// An empty cell is "not finite" (NaN), as the CSV writes it.
bool number(std::string_view cell, double& out) {
  if (cell.empty()) {
    out = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), out);
  return ec == std::errc() && end == cell.data() + cell.size();
}

}  // namespace

FigureData parse_figure_csv(std::string_view csv) {
  FigureData f;
  std::map<std::pair<std::string, std::string>, std::size_t> index;
  std::size_t line_no = 0, columns = 0;
  for (std::size_t at = 0; at < csv.size();) {
    auto nl = csv.find('\n', at);
    if (nl == std::string_view::npos) nl = csv.size();
    std::string_view line = csv.substr(at, nl - at);
    at = nl + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty()) continue;
    const auto cells = split(line);
    if (line_no == 1) {
      if (cells.size() < 4 || cells.size() > 5 || cells[0] != "panel" || cells[1] != "series")
        throw std::invalid_argument("figure CSV: line 1 is not 'panel,series,X,Y[,Y_lower]'");
      f.x_column = cells[2];
      f.y_column = cells[3];
      columns = cells.size();
      continue;
    }
    if (cells.size() != columns)
      throw std::invalid_argument("figure CSV: line " + std::to_string(line_no) + " has " +
                                  std::to_string(cells.size()) + " cells, not " + std::to_string(columns));
    double x = 0, y = 0, low = std::numeric_limits<double>::quiet_NaN();
    if (!number(cells[2], x) || !number(cells[3], y) || (columns == 5 && !number(cells[4], low)))
      throw std::invalid_argument("figure CSV: line " + std::to_string(line_no) + " holds a value that is not a number");
    const auto key = std::make_pair(std::string(cells[0]), std::string(cells[1]));
    auto it = index.find(key);
    if (it == index.end()) {
      it = index.emplace(key, f.series.size()).first;
      f.series.push_back({key.first, key.second, FigureSeries::Kind::Line, {}, {}, {}});
      bool seen = false;
      for (const std::string& p : f.panels) seen = seen || p == key.first;
      if (!seen) f.panels.push_back(key.first);
    }
    FigureSeries& s = f.series[it->second];
    s.x.push_back(x);
    s.y.push_back(y);
    s.y_low.push_back(low);
  }
  if (line_no == 0) throw std::invalid_argument("figure CSV: empty");
  for (FigureSeries& s : f.series) {
    bool band = false, ordered = true;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      band = band || std::isfinite(s.y_low[i]);
      if (i > 0 && s.x[i] < s.x[i - 1]) ordered = false;
    }
    if (band) s.kind = FigureSeries::Kind::Band;
    else if (s.name.rfind("raw", 0) == 0 || !ordered) s.kind = FigureSeries::Kind::Points;
    if (!band) s.y_low.clear();
  }
  return f;
}

std::string axis_label(std::string_view column) {
  static const std::pair<std::string_view, std::string_view> units[] = {
      {"_deg_per_s", " (°/s)"}, {"_deg", " (°)"},   {"_mNm", " (mN·m)"}, {"_mm_per_s", " (mm/s)"},
      {"_mm", " (mm)"},         {"_N", " (N)"},     {"_s", " (s)"},      {"_rows", " (rows)"}};
  for (const auto& [suffix, unit] : units) {
    if (column.size() > suffix.size() && column.substr(column.size() - suffix.size()) == suffix) {
      std::string name(column.substr(0, column.size() - suffix.size()));
      for (char& c : name)
        if (c == '_') c = ' ';
      return name + std::string(unit);
    }
  }
  std::string name(column);
  for (char& c : name)
    if (c == '_') c = ' ';
  return name;
}

}  // namespace knoblab::ui
