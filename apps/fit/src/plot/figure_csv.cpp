#include "knoblab/fit/plot/figure_csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "knoblab/fit/plot/text.hpp"

namespace knoblab::fit::plot {

namespace {

// A CSV field, quoted when it holds a comma, a quote or a line break.
std::string field(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string value(const std::vector<double>& v, std::size_t i) {
  if (i >= v.size() || !std::isfinite(v[i])) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v[i]);
  return buf;
}

}  // namespace

std::string figure_csv(const Figure& fig) {
  std::string csv;
  if (fig.panels.empty()) {
    for (const auto& row : fig.text.table) {
      for (std::size_t c = 0; c < row.size(); ++c) csv += (c ? "," : "") + field(plain(row[c]));
      csv += "\n";
    }
    return csv;
  }
  bool bands = false;
  for (const Panel& p : fig.panels)
    for (const Series& s : p.series) bands = bands || s.mark == Mark::Fill;
  csv = "panel,series," + field(fig.x_column) + "," + field(fig.y_column) +
        (bands ? "," + field(fig.y_low_column) : "") + "\n";
  for (const Panel& p : fig.panels) {
    for (const Series& s : p.series) {
      const bool has_y = s.mark != Mark::VLines, has_low = s.mark == Mark::Fill;
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        csv += p.name + "," + s.name + "," + value(s.x, i) + "," + (has_y ? value(s.y, i) : "");
        if (bands) csv += "," + (has_low ? value(s.y_low, i) : "");
        csv += "\n";
      }
    }
  }
  return csv;
}

}  // namespace knoblab::fit::plot
