// The established libraries apps/stats is checked against, run at test time
// on the test's own data: scipy.stats (scipy_reference.py) and base R
// (rm_anova_reference.R). Data goes over as CSV (shortest round-trip
// decimals); results come back as "name value" lines at full precision.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace knoblab::stats::test {

using Table = std::vector<std::vector<double>>;  // rows of a CSV
using Values = std::map<std::string, double>;

// python3 scipy_reference.py CHECK data.csv. Throws std::runtime_error when
// python3 was not found at configure time or the script fails.
Values scipy_reference(const std::string& check, const Table& data);

// Rscript rm_anova_reference.R data.csv (rows: subjects, columns:
// conditions). Throws as scipy_reference does.
Values r_rm_anova_reference(const Table& data);

// Columns as rows, for pairs kept as two vectors.
Table columns(const std::vector<double>& x, const std::vector<double>& y);

// |actual − expected| ≤ relative·|expected| (or ≤ relative when expected is
// 0), reported with both values and the name.
void expect_relative(double actual, const Values& reference, const std::string& name,
                     double relative = 1e-9);

}  // namespace knoblab::stats::test
