// The pointing tidy table grouped the ways the report needs it: by
// rendering, by trial, by participant. Shared by the report and its plots,
// so both read the rows the same way.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "knoblab/study/pointing_report.hpp"
#include "knoblab/study/tidy.hpp"

namespace knoblab::study::detail {

struct PointingTrial {
  std::size_t participant = 0, rendering = 0;  // indices into PointingTables
  int rating = 0;
  double movement_time_s = 0;       // mean over its acquisitions
  std::optional<double> emg_uV, sc_uS;  // mean over its rows that have one
};

struct PointingTables {
  std::vector<std::string> renderings;    // level order, the control first
  std::vector<std::string> participants;  // in the order the rows first name them
  std::vector<std::vector<const PointingRow*>> rows_by_rendering;  // analysed rows only
  std::vector<PointingTrial> trials;
  // [participant][rendering]: movement times of its acquisitions, ratings of its trials.
  std::vector<std::vector<std::vector<double>>> times, ratings;
  std::vector<std::size_t> complete;  // participants with every rendering
  std::size_t acquisitions = 0;
};

// The analysed (non-practice) rows grouped. Throws std::invalid_argument as
// pointing_report documents for an order that does not match the rows,
// rows of a trial that disagree, no analysed rows.
PointingTables tabulate(std::span<const PointingRow> rows, const PointingReportOptions& options);

}  // namespace knoblab::study::detail
