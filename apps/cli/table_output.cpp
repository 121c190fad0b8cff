#include "table_output.hpp"

#include <cstdio>

#include "knoblab/interchange/number_text.hpp"

namespace knoblab::cli {

namespace {

std::string csv_field(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_number_float()) return interchange::shortest(v.get<double>());
  if (!v.is_string()) return v.dump();
  const std::string s = v.get<std::string>();
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

std::string to_csv(const Table& table) {
  std::string out;
  for (std::size_t i = 0; i < table.columns.size(); ++i)
    out += (i ? "," : "") + csv_field(table.columns[i]);
  out += "\n";
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) out += (i ? "," : "") + csv_field(row[i]);
    out += "\n";
  }
  return out;
}

nlohmann::json row_object(const Table& table, std::size_t row) {
  nlohmann::json o = nlohmann::json::object();
  const auto& values = table.rows.at(row);
  for (std::size_t i = 0; i < values.size() && i < table.columns.size(); ++i) o[table.columns[i]] = values[i];
  return o;
}

std::string to_json(const Table& table) {
  nlohmann::json all = nlohmann::json::array();
  for (std::size_t r = 0; r < table.rows.size(); ++r) all.push_back(row_object(table, r));
  // Replacement for invalid UTF-8 in stored text, so the output is always valid JSON.
  return all.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

bool print_table_if_asked(const Args& args, const Table& table) {
  const bool json = args.has("json"), csv = args.has("csv");
  if (json && csv) throw UsageError("give --json or --csv, not both");
  if (!json && !csv) return false;
  const std::string text = json ? to_json(table) : to_csv(table);
  std::fwrite(text.data(), 1, text.size(), stdout);
  return true;
}

}  // namespace knoblab::cli
