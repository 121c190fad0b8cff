// knoblab fits / fit-export: the fits in a store, and one fit's result JSON
// and report files back out as files.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.hpp"
#include "result_files.hpp"
#include "result_view.hpp"
#include "store_open.hpp"
#include "table_output.hpp"
#include "knoblab/interchange/atomic_file.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::cli {

const CommandSpec kFitsSpec{
    "fits", "--db FILE.sqlite [--capture ID] [--json | --csv]",
    "List the stored fits with the key figures of each, and their provenance.\n"
    "For each: model, when, rms error, percent fit, detents per revolution, how many\n"
    "report files it has, and its provenance: the knoblab version that made it and the\n"
    "first 12 hex digits of its input's SHA-256 ('-' for fits stored before schema 7;\n"
    "knoblab results ID --kind fit shows all of it).",
    {{"db", true, "sqlite store"},
     {"capture", true, "only the fits of this capture"},
     {"json", false, "print the list as a JSON array (SI units, the full SHA-256)"},
     {"csv", false, "print the list as CSV under a header (SI units, the full SHA-256)"}},
    0, 0, false, {"knoblab fits --db lab.sqlite --capture 1", "knoblab fits --db lab.sqlite --csv > fits.csv"}};

const CommandSpec kFitExportSpec{
    "fit-export", "FIT --db FILE [--json OUT|-] [--report DIR]",
    "Write a stored fit's result JSON and report files out.\n"
    "The result JSON is the 'knoblab fit --json' format; the stored report files (plots,\n"
    "fit.json, render model) are written byte for byte into DIR.",
    {{"db", true, "sqlite store"},
     {"json", true, "file for the result JSON; '-' for stdout"},
     {"report", true, "directory for the report files (created if missing)"}},
    1, 1, false, {"knoblab fit-export 1 --db lab.sqlite --json fit.json --report fit-1/"}};

int run_fits(const Args& args) {
  std::optional<std::int64_t> capture;
  if (auto c = args.get("capture")) capture = id_arg("--capture", "capture", *c);
  store::Store db = open_store_to_read(args.require("db"));
  if (capture && !db.capture_info(*capture))
    throw std::runtime_error("no capture " + std::to_string(*capture) + " in the store");
  const auto fits = capture ? db.list_fits(*capture) : db.list_all_fits();
  Table table{{"id", "capture_id", "model", "created_at", "rmse_Nm", "fit_percent", "detents_per_rev", "files",
               "tool_version", "input_sha256"},
              {}};
  for (const auto& f : fits) {
    const auto result = nlohmann::json::parse(f.result, nullptr, /*allow_exceptions=*/false);
    const auto value = [](std::optional<double> v) { return v ? nlohmann::json(*v) : nlohmann::json(); };
    table.rows.push_back({f.id, f.capture_id, f.model, f.created_at, value(number_at(result, {"rmse_Nm"})),
                          value(number_at(result, {"fit_percent"})), value(number_at(result, {"detents", "per_rev"})),
                          f.file_count, f.provenance ? nlohmann::json(f.provenance->tool_version) : nlohmann::json(),
                          f.provenance ? nlohmann::json(f.provenance->input_sha256) : nlohmann::json()});
  }
  if (print_table_if_asked(args, table)) return 0;
  std::printf("%6s %8s  %-8s %-24s %10s %6s %11s %5s  %-25s %s\n", "id", "capture", "model", "created",
              "rmse_Nm", "fit_%", "detents/rev", "files", "version", "input");
  for (const auto& f : fits) {
    const auto result = nlohmann::json::parse(f.result, nullptr, /*allow_exceptions=*/false);
    std::printf("%6lld %8lld  %-8s %-24s %10s %6s %11s %5lld  %-25s %s\n", static_cast<long long>(f.id),
                static_cast<long long>(f.capture_id), f.model.c_str(), f.created_at.c_str(),
                figure(number_at(result, {"rmse_Nm"}), 4, false).c_str(),
                figure(number_at(result, {"fit_percent"}), 1, true).c_str(),
                figure(number_at(result, {"detents", "per_rev"}), 2, true).c_str(),
                static_cast<long long>(f.file_count), version_of(f.provenance).c_str(),
                short_sha256(f.provenance).c_str());
  }
  return 0;
}

int run_fit_export(const Args& args) {
  const std::int64_t id = id_arg("FIT", "fit", args.positionals().at(0));
  const auto json_out = args.get("json");
  const auto report_dir = args.get("report");
  if (!json_out && !report_dir) throw UsageError("give --json OUT (or -) and/or --report DIR");
  if (json_out && json_out->empty()) throw UsageError("--json needs a file name or '-'");
  if (report_dir && report_dir->empty()) throw UsageError("--report needs a directory");
  store::Store db = open_store_to_read(args.require("db"));

  // Everything is read and checked before anything is written.
  const auto fit = db.fit_info(id);
  if (!fit) throw std::runtime_error("no fit " + std::to_string(id) + " in the store");
  std::vector<store::FitFile> files;
  if (report_dir) {
    files = db.load_fit_files(id);
    if (files.empty())
      throw std::runtime_error("fit " + std::to_string(id) +
                               " has no stored report files (use --json for its result)");
    for (const auto& f : files)
      if (!plain_file_name(f.name))
        throw std::runtime_error("fit " + std::to_string(id) + ": refusing to write a file named '" +
                                 f.name + "'");
  }

  const bool quiet = json_out == std::optional<std::string>("-");  // stdout is the JSON
  if (json_out) {
    const std::string text = fit->result + "\n";
    if (*json_out == "-") {
      std::fwrite(text.data(), 1, text.size(), stdout);
    } else {
      interchange::write_file_atomically(*json_out, text);
      std::printf("fit %lld: result JSON written to %s\n", static_cast<long long>(id),
                  json_out->c_str());
    }
  }
  if (report_dir) {
    write_result_files(files, *report_dir);
    if (!quiet)
      std::printf("fit %lld: %zu report files (%zu bytes) written to %s\n",
                  static_cast<long long>(id), files.size(), total_bytes(files), report_dir->c_str());
  }
  return 0;
}

}  // namespace knoblab::cli
