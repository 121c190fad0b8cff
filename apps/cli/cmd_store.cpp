// knoblab import / export / list: move captures between CSV files and the store.
#include <charconv>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cancel.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "store_open.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::cli {

const CommandSpec kImportSpec{
    "import", "FILE.csv --db FILE [--knob NAME] [--mode lab|tripod]",
    "Import an interchange CSV into the store as one complete capture.\n"
    "The file is validated first; a bad file changes nothing in the store.\n"
    "Samples go in in short transactions, so hapticd goes on recording into the\n"
    "same store meanwhile; until the import ends the capture is listed as\n"
    "'recording' (an import that is killed is marked incomplete on the next open;\n"
    "one cancelled with Ctrl-C takes its samples out again, exit status 130).",
    {{"db", true, "sqlite store (created if missing)"},
     {"knob", true, "knob name to file the capture under"},
     {"mode", true, "lab (default) or tripod"},
     kQuietOption},
    1, 1};

const CommandSpec kExportSpec{
    "export", "CAPTURE --db FILE --out FILE.csv",
    "Write a stored capture as interchange CSV.\n"
    "The capture's fields (status, end_reason, ...) become '# key: value' lines;\n"
    "the loop's per-sample flags, when any is set, a 'flags' column.\n"
    "Only reads the store: never waits for a writer.",
    {{"db", true, "sqlite store"}, {"out", true, "CSV file to write"}},
    1, 1};

const CommandSpec kListSpec{
    "list", "--db FILE",
    "List the captures in a store.\n"
    "An incomplete capture's last column says why (e.g. 'fault: estop').\n"
    "Only reads the store: never waits for a writer.",
    {{"db", true, "sqlite store"}}, 0, 0};

namespace {

// A CSV that knoblab wrote says which knob, mounting and stimulus it holds;
// those become the capture's own fields, the other comments its metadata.
store::NewCapture describe_import(const interchange::Capture& capture, const Args& args) {
  store::NewCapture info;
  nlohmann::json rest = nlohmann::json::object();
  for (const auto& [key, value] : capture.metadata) {
    const bool is_object = nlohmann::json::accept(value) && nlohmann::json::parse(value).is_object();
    if (key == "knob") info.knob = value;
    else if (key == "mode" && (value == "lab" || value == "tripod")) info.mode = value;
    else if (key == "stimulus" && is_object) info.stimulus = value;
    else if (key == "orientation" && is_object) info.orientation = value;
    else if (key == "calibration" && is_object) info.calibration = value;
    else if (key == "metadata" && is_object) rest.update(nlohmann::json::parse(value));
    else rest[key] = value;
  }
  info.metadata = rest.dump();
  if (auto knob = args.get("knob")) info.knob = *knob;
  if (auto mode = args.get("mode")) info.mode = *mode;
  if (info.mode != "lab" && info.mode != "tripod") throw UsageError("--mode must be 'lab' or 'tripod'");
  return info;
}

std::int64_t capture_id_arg(const std::string& text) {
  std::int64_t id = 0;
  auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (ec != std::errc() || p != text.data() + text.size() || id <= 0)
    throw UsageError("CAPTURE must be a capture id (a positive integer), got '" + text + "'");
  return id;
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
  const std::int64_t id = capture_id_arg(args.positionals().at(0));
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
  std::printf("%6s  %-20s %-7s %-10s %9s %9s  %-24s  %s\n", "id", "knob", "mode", "status",
              "samples", "rate Hz", "started", "why incomplete");
  for (const auto& c : db.list_captures())
    std::printf("%6lld  %-20s %-7s %-10s %9lld %9.0f  %-24s  %s\n", static_cast<long long>(c.id),
                c.knob.empty() ? "-" : c.knob.c_str(), c.mode.c_str(), c.status.c_str(),
                static_cast<long long>(c.sample_count), c.rate_hz, c.started_at.c_str(),
                c.end_reason ? c.end_reason->c_str() : (c.status == "incomplete" ? "?" : "-"));
  return 0;
}

}  // namespace knoblab::cli
