// knoblab compare: two knobs side by side — captures fitted (or their stored
// fits), fit results, render models or model files — with their 95 %
// intervals and whether they overlap; overlaid plots with --report.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "capture_input.hpp"
#include "commands.hpp"
#include "compare_plot.hpp"
#include "figure_args.hpp"
#include "compare_side.hpp"
#include "fit_run.hpp"

namespace knoblab::cli {

const CommandSpec kCompareSpec{
    "compare",
    "A B [--db FILE.sqlite] [--json OUT.json|-] [--report DIR [--format pdf,svg,png] [--size WxHmm] [--dpi N]]",
    "Compare two knobs parameter by parameter, with their intervals, and overlay them.\n"
    "Each of A and B is a capture (CSV file, or a capture id with --db: its latest\n"
    "stored fit, else fitted now), a fit's result\n"
    "JSON, a render model or a model file (discrepancy --model-out). Prints each\n"
    "parameter with its 95 % interval (mN·m, rad; SI in --json) and whether A's and\n"
    "B's intervals overlap (with an interval on one side only: whether the other's\n"
    "value lies inside it). --report writes torque_position and torque_velocity, the\n"
    "two overlaid, as PDF, SVG and PNG with their data as CSV (docs/fit.md, docs/figures.md).",
    with_figure_options({{"db", true, "sqlite store the capture ids are in"},
     {"json", true, "write the comparison as JSON (SI); '-' for stdout"},
     {"report", true, "directory for the overlaid figures"},
     {"alpha", true, "captures: accel (default: the α column, when there is one) or encoder (θ'')",
      "accel|encoder"},
     {"no-filter", false, "captures: skip the Table 6 low-pass filters"}}),
    2, 2, false,
    {"knoblab compare knob.csv fit.json", "knoblab compare 1 2 --db lab.sqlite --report compare/"}};

namespace {

struct Row {
  std::string name;
  const SideParam* a = nullptr;
  const SideParam* b = nullptr;
  std::optional<bool> overlap;  // none: no interval to judge by
};

const SideParam* find(const CompareSide& s, const std::string& name) {
  for (const SideParam& p : s.params)
    if (p.name == name) return &p;
  return nullptr;
}

bool inside(double v, const std::array<double, 2>& ci) { return v >= ci[0] && v <= ci[1]; }

std::optional<bool> overlap_of(const SideParam* a, const SideParam* b) {
  if (!a || !b) return std::nullopt;
  if (a->ci95 && b->ci95) return std::max((*a->ci95)[0], (*b->ci95)[0]) <= std::min((*a->ci95)[1], (*b->ci95)[1]);
  if (a->ci95) return inside(b->value, *a->ci95);
  if (b->ci95) return inside(a->value, *b->ci95);
  return std::nullopt;
}

// A's parameters in its order, then those only B has.
std::vector<Row> rows_of(const CompareSide& a, const CompareSide& b) {
  std::vector<Row> rows;
  for (const SideParam& p : a.params) rows.push_back({p.name, &p, find(b, p.name), {}});
  for (const SideParam& p : b.params)
    if (!find(a, p.name)) rows.push_back({p.name, nullptr, &p, {}});
  for (Row& r : rows) r.overlap = overlap_of(r.a, r.b);
  return rows;
}

std::string cell(const SideParam* p, double scale) {
  if (!p) return "-";
  char buf[96];
  if (p->ci95)
    std::snprintf(buf, sizeof buf, "%.5g [%.5g, %.5g]", p->value * scale, (*p->ci95)[0] * scale,
                  (*p->ci95)[1] * scale);
  else
    std::snprintf(buf, sizeof buf, "%.5g", p->value * scale);
  return buf;
}

// `s` padded to `width` characters on screen (printf pads bytes; units hold
// multi-byte ones such as · and ²).
std::string pad(const std::string& s, std::size_t width) {
  std::size_t shown = 0;
  for (const char c : s) shown += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
  return s + std::string(width > shown ? width - shown : 0, ' ');
}

void print_table(const CompareSide& a, const CompareSide& b, const std::vector<Row>& rows) {
  std::printf("A: %s (%s)\nB: %s (%s)\n", a.label.c_str(), a.origin.c_str(), b.label.c_str(), b.origin.c_str());
  std::printf("  %-24s %s %-34s %-34s %s\n", "parameter", pad("unit", 14).c_str(), "A value [95% CI]",
              "B value [95% CI]", "overlap");
  std::vector<std::string> disjoint;
  std::size_t judged = 0;
  for (const Row& r : rows) {
    // Effects' parameters ("stribeck.excess") are shown in SI.
    const bool effect = r.name.find('.') != std::string::npos;
    const fit::Unit p = effect ? fit::Unit{.scale = 1.0, .text = "SI"} : presentation(r.name);
    const char* verdict = !r.overlap ? "-" : *r.overlap ? "yes" : "NO";
    std::printf("  %-24s %s %-34s %-34s %s\n", r.name.c_str(), pad(std::string(p.text), 14).c_str(),
                cell(r.a, p.scale).c_str(), cell(r.b, p.scale).c_str(), verdict);
    if (r.overlap) ++judged;
    if (r.overlap == false) disjoint.push_back(r.name);
  }
  std::printf("%zu of %zu parameters judged by their intervals overlap", judged - disjoint.size(), judged);
  if (disjoint.empty()) {
    std::printf("\n");
  } else {
    std::string list;
    for (const auto& n : disjoint) list += (list.empty() ? "" : ", ") + n;
    std::printf("; apart: %s\n", list.c_str());
  }
}

nlohmann::ordered_json side_json(const SideParam* p) {
  if (!p) return nullptr;
  nlohmann::ordered_json j = {{"value", p->value}, {"ci95", nullptr}};
  if (p->ci95) j["ci95"] = {(*p->ci95)[0], (*p->ci95)[1]};
  return j;
}

std::string comparison_json(const CompareSide& a, const CompareSide& b, const std::vector<Row>& rows) {
  using nlohmann::ordered_json;
  ordered_json params = ordered_json::array(), apart = ordered_json::array();
  for (const Row& r : rows) {
    params.push_back({{"name", r.name},
                      {"a", side_json(r.a)},
                      {"b", side_json(r.b)},
                      {"overlap", r.overlap ? ordered_json(*r.overlap) : ordered_json(nullptr)}});
    if (r.overlap == false) apart.push_back(r.name);
  }
  const ordered_json j = {{"a", {{"source", a.label}, {"origin", a.origin}}},
                          {"b", {{"source", b.label}, {"origin", b.origin}}},
                          {"params", params},
                          {"apart", apart}};
  return j.dump(2);
}

}  // namespace

int run_compare(const Args& args) {
  if (args.get("report") == std::optional<std::string>("")) throw UsageError("--report needs a directory");
  const fit::plot::FigureOptions figures = figure_options(args);  // checked before any work
  const CompareSide a = read_side(args.positionals()[0], args);
  const CompareSide b = read_side(args.positionals()[1], args);
  const std::vector<Row> rows = rows_of(a, b);
  const bool json_to_stdout = args.get("json") == std::optional<std::string>("-");
  if (!json_to_stdout) print_table(a, b, rows);
  if (auto out = args.get("json")) write_text(*out, comparison_json(a, b, rows));
  if (auto dir = args.get("report")) {
    const auto files = write_compare_plots(*dir, a, b, figures);
    if (!json_to_stdout) std::printf("report: %zu files in %s\n", files.size(), dir->c_str());
  }
  return 0;
}

}  // namespace knoblab::cli
