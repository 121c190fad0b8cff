// Listings as data: the same rows printed as a JSON array of objects or as CSV
// (RFC 4180 quoting), in SI units, for list, inspect, fits and results.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "args.hpp"

namespace knoblab::cli {

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<nlohmann::json>> rows;  // null, number or string per column
};

std::string to_csv(const Table& table);
std::string to_json(const Table& table);  // one object per row, keys = columns
nlohmann::json row_object(const Table& table, std::size_t row);

// --json or --csv as the command asked (both is a UsageError); false when
// neither was asked for, so the caller prints its text form.
bool print_table_if_asked(const Args& args, const Table& table);

}  // namespace knoblab::cli
