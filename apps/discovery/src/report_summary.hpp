// The discrepancy report's summary as text: one table (base, after each
// finding, final) and the findings' sentences, shared by summary.png and
// summary.md. Internal to knoblab_discovery_report.
#pragma once

#include <string>
#include <vector>

#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/discovery/whiteness.hpp"
#include "knoblab/fit/fit_data.hpp"

namespace knoblab::discovery::detail {

struct SummaryText {
  std::vector<std::vector<std::string>> table;  // header first ('\n': two lines); mN·m, %
  std::vector<std::string> findings;  // one sentence each, or that nothing is missing
  std::vector<std::string> notes;     // which rows, lag spacing
};

SummaryText summary_text(const fit::FitData& data, const DiscrepancyResult& r,
                         const ResidualFigures& before, const ResidualFigures& after);

std::string summary_markdown(const std::string& title, const SummaryText& s);

// "0.43", "3.1e-05", "< 1e-12", "–" (NaN).
std::string format_p(double p);

}  // namespace knoblab::discovery::detail
