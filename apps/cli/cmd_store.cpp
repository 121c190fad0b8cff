// knoblab import / export / list: move captures between CSV files and the store.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cancel.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "store_open.hpp"
#include "table_output.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::cli {

const CommandSpec kImportSpec{
    "import", "FILE.csv --db FILE.sqlite [--knob NAME] [--mode lab|tripod]",
    "Import an interchange CSV into the store as one complete capture.\n"
    "The file is validated first; a bad file changes nothing in the store.\n"
    "Samples go in in short transactions, so hapticd goes on recording into the\n"
    "same store meanwhile; until the import ends the capture is listed as\n"
    "'recording' (an import that is killed is marked incomplete on the next open;\n"
    "one cancelled with Ctrl-C takes its samples out again, exit status 130).",
    {{"db", true, "sqlite store (created if missing)"},
     {"knob", true, "knob name to file the capture under"},
     {"mode", true, "lab (default) or tripod", "lab|tripod"},
     kQuietOption},
    1, 1, true,
    {"knoblab import knob.csv --db lab.sqlite --knob 'fan knob'"}};

const CommandSpec kExportSpec{
    "export", "CAPTURE --db FILE.sqlite --out FILE.csv",
    "Write a stored capture as interchange CSV.\n"
    "The capture's fields (status, end_reason, ...) become '# key: value' lines;\n"
    "the loop's per-sample flags, when any is set, a 'flags' column.\n"
    "Only reads the store: never waits for a writer.",
    {{"db", true, "sqlite store"}, {"out", true, "CSV file to write"}},
    1, 1, false,
    {"knoblab export 1 --db lab.sqlite --out capture-1.csv"}};

const CommandSpec kListSpec{
    "list", "--db FILE.sqlite [--json | --csv]",
    "List the captures in a store.\n"
    "An incomplete capture's last column says why (e.g. 'fault: estop').\n"
    "Only reads the store: never waits for a writer.",
    {{"db", true, "sqlite store"},
     {"json", false, "print the list as a JSON array"},
     {"csv", false, "print the list as CSV under a header"}},
    0, 0, false,
    {"knoblab list --db lab.sqlite", "knoblab list --db lab.sqlite --csv > captures.csv"}};

namespace {

// What `knoblab export` writes about the row a capture had in its store:
// kept on import as where the file came from, not as this capture's own.
bool exported_field(const std::string& key) {
  for (const char* k : {"capture_id", "rate_hz", "source", "status", "end_reason", "started_at", "finished_at",
                        "sample_count"})
    if (key == k) return true;
  return false;
}

// A CSV that knoblab wrote says which knob, mounting and stimulus it holds;
// those become the capture's own fields, the other comments its metadata.
store::NewCapture describe_import(const interchange::Capture& capture, const Args& args) {
  store::NewCapture info;
  // In file order; a key given twice keeps all its values (an array), free
  // comments go under "comments": nothing the file said is lost.
  nlohmann::ordered_json rest = nlohmann::ordered_json::object();
  const auto keep = [&rest](const std::string& key, const std::string& value) {
    auto it = rest.find(key);
    if (it == rest.end()) rest[key] = value;
    else if (it->is_array()) it->push_back(value);
    else *it = nlohmann::ordered_json::array({*it, value});
  };
  for (const auto& [key, value] : capture.metadata) {
    const bool is_object = nlohmann::json::accept(value) && nlohmann::json::parse(value).is_object();
    if (key == "knob") info.knob = value;
    else if (key == "mode" && (value == "lab" || value == "tripod")) info.mode = value;
    else if (key == "stimulus" && is_object) info.stimulus = value;
    else if (key == "orientation" && is_object) info.orientation = value;
    else if (key == "calibration" && is_object) info.calibration = value;
    else if (key == "metadata" && is_object) rest.update(nlohmann::ordered_json::parse(value));
    else if (exported_field(key)) rest["exported_from"][key] = value;
    else if (key.empty()) {
      if (!rest.contains("comments")) rest["comments"] = nlohmann::ordered_json::array();
      rest["comments"].push_back(value);
    } else {
      keep(key, value);
    }
  }
  info.metadata = rest.dump();
  if (auto knob = args.get("knob")) info.knob = *knob;
  if (auto mode = args.get("mode")) info.mode = *mode;
  if (info.mode != "lab" && info.mode != "tripod") throw UsageError("--mode must be 'lab' or 'tripod'");
  return info;
}


}  // namespace

int run_import(const Args& args) {
  const std::string file = args.positionals().at(0);
  const std::string db_path = args.require("db");
  Progress progress = Progress::on_stderr(args, "import");
  const CancelOnSignal cancel;
  progress.show("reading " + file);
  // Parse and validate everything before the store is even opened.
  const interchange::Capture capture = interchange::read_csv(file);
  const store::NewCapture info = describe_import(capture, args);
  throw_if_cancelled();
  store::Store db = store::Store::open(db_path);
  store::ImportOptions options;
  // Throwing here takes the partial capture out again (import_capture).
  options.on_commit = [&](std::int64_t committed) {
    progress.show("importing", static_cast<std::size_t>(committed), capture.size());
    throw_if_cancelled();
  };
  const std::int64_t id = db.import_capture(capture, info, options);
  progress.clear();
  std::printf("imported %s: %zu samples as capture %lld%s%s\n", file.c_str(), capture.size(),
              static_cast<long long>(id), capture.omega_derived ? " (omega derived)" : "",
              capture.alpha_derived ? " (alpha derived)" : "");
  return 0;
}

int run_export(const Args& args) {
  const std::int64_t id = parse_id("CAPTURE", args.positionals().at(0));
  const std::string out = args.require("out");
  store::Store db = open_store_to_read(args.require("db"));
  if (!db.capture_info(id)) throw std::runtime_error("no capture " + std::to_string(id) + " in the store");
  const interchange::Capture capture = db.load_samples(id);
  interchange::write_csv(capture, std::filesystem::path(out));
  std::printf("exported capture %lld: %zu samples to %s\n", static_cast<long long>(id), capture.size(),
              out.c_str());
  return 0;
}

int run_list(const Args& args) {
  store::Store db = open_store_to_read(args.require("db"));
  const auto captures = db.list_captures();
  Table table{{"id", "knob", "mode", "status", "samples", "rate_hz", "started_at", "end_reason"}, {}};
  for (const auto& c : captures)
    table.rows.push_back({c.id, c.knob.empty() ? nlohmann::json() : nlohmann::json(c.knob), c.mode, c.status,
                          c.sample_count, c.rate_hz, c.started_at,
                          c.end_reason ? nlohmann::json(*c.end_reason) : nlohmann::json()});
  if (print_table_if_asked(args, table)) return 0;
  std::printf("%6s  %-20s %-7s %-10s %9s %9s  %-24s  %s\n", "id", "knob", "mode", "status",
              "samples", "rate Hz", "started", "why incomplete");
  for (const auto& c : captures)
    std::printf("%6lld  %-20s %-7s %-10s %9lld %9.0f  %-24s  %s\n", static_cast<long long>(c.id),
                c.knob.empty() ? "-" : c.knob.c_str(), c.mode.c_str(), c.status.c_str(),
                static_cast<long long>(c.sample_count), c.rate_hz, c.started_at.c_str(),
                c.end_reason ? c.end_reason->c_str() : (c.status == "incomplete" ? "?" : "-"));
  return 0;
}

}  // namespace knoblab::cli
