// knoblab results: the stored results (fits and discrepancy results)
// together, with their provenance; one of them written out whole.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "result_files.hpp"
#include "result_view.hpp"
#include "store_open.hpp"
#include "knoblab/interchange/atomic_file.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::cli {

const CommandSpec kResultsSpec{
    "results", "--db FILE.sqlite [--json] | ID --kind fit|discrepancy --db FILE.sqlite [--json] [--out DIR]",
    "List the stored results, fits and discrepancy results together, or show one.\n"
    "The list, oldest first: kind, id, capture, when, the knoblab version that made it, how many report\n"
    "files it has and its key figure (mN·m). With an ID and its --kind, one result:\n"
    "its provenance in full (the SHA-256 of the capture's samples it analysed, the\n"
    "options it ran with) and its files; --out DIR writes its result.json,\n"
    "provenance.json and report files (DIR/report/) into DIR. --json prints the same\n"
    "as JSON records (docs/store.md).",
    {{"db", true, "sqlite store"},
     {"json", false, "JSON records instead of text"},
     {"kind", true, "fit or discrepancy: which result ID names", "fit|discrepancy"},
     {"out", true, "with ID: the directory to write the result into (created if missing)", "DIR"}},
    0, 1, false,
    {"knoblab results --db lab.sqlite", "knoblab results 2 --kind discrepancy --db lab.sqlite --out result-2/"}};

namespace {

// One stored result, either kind.
struct Result {
  std::string kind;
  std::int64_t id = 0, capture_id = 0, files = 0;
  std::string created_at, version, key;
  nlohmann::json record;
};

std::vector<Result> all_results(store::Store& db) {
  std::vector<Result> out;
  for (const auto& f : db.list_all_fits())
    out.push_back({"fit", f.id, f.capture_id, f.file_count, f.created_at, version_of(f.provenance),
                   fit_key_figure(f), fit_record(f)});
  for (const auto& d : db.list_all_discrepancies())
    out.push_back({"discrepancy", d.id, d.capture_id, d.file_count, d.created_at,
                   version_of(d.provenance), discrepancy_key_figure(d), discrepancy_record(d)});
  // Oldest first; fits before discrepancy results stored in the same millisecond.
  std::stable_sort(out.begin(), out.end(), [](const Result& a, const Result& b) {
    return a.created_at < b.created_at;
  });
  return out;
}

int list(store::Store& db, bool json) {
  const std::vector<Result> results = all_results(db);
  if (json) {
    nlohmann::json all = nlohmann::json::array();
    for (const Result& r : results) all.push_back(r.record);
    std::printf("%s\n", all.dump(2).c_str());
    return 0;
  }
  std::printf("%-12s %6s %8s  %-24s  %-25s %5s  %s\n", "kind", "id", "capture", "created", "version",
              "files", "key figure");
  for (const Result& r : results)
    std::printf("%-12s %6lld %8lld  %-24s  %-25s %5lld  %s\n", r.kind.c_str(), static_cast<long long>(r.id),
                static_cast<long long>(r.capture_id), r.created_at.c_str(), r.version.c_str(),
                static_cast<long long>(r.files), r.key.c_str());
  return 0;
}

// One result, read whole before anything is written.
struct One {
  std::string name;  // "fit 3"
  std::string result;
  nlohmann::json record;
  std::string key;
  std::vector<store::ResultFile> files;
};

One load_one(store::Store& db, const std::string& kind, std::int64_t id) {
  One one;
  one.name = kind + " " + std::to_string(id);
  if (kind == "fit") {
    const auto f = db.fit_info(id);
    if (!f) throw std::runtime_error("no fit " + std::to_string(id) + " in the store");
    one.result = f->result;
    one.record = fit_record(*f);
    one.key = fit_key_figure(*f);
    one.files = db.load_fit_files(id);
  } else {
    const auto d = db.discrepancy_info(id);
    if (!d) throw std::runtime_error("no discrepancy " + std::to_string(id) + " in the store");
    one.result = d->result;
    one.record = discrepancy_record(*d);
    one.key = discrepancy_key_figure(*d);
    one.files = db.load_discrepancy_files(id);
  }
  one.record["report"] = nlohmann::json::array();
  for (const auto& f : one.files) one.record["report"].push_back({{"name", f.name}, {"bytes", f.bytes.size()}});
  return one;
}

void print_one(const One& one) {
  const nlohmann::json& r = one.record;
  std::printf("%s of capture %lld, stored %s\n", one.name.c_str(), r["capture_id"].get<long long>(),
              r["created_at"].get<std::string>().c_str());
  if (r.contains("heldout_capture_id") && !r["heldout_capture_id"].is_null())
    std::printf("  held out:  capture %lld\n", r["heldout_capture_id"].get<long long>());
  if (r["tool_version"].is_null()) {
    std::printf("  provenance: none (stored before knoblab kept it)\n");
  } else {
    std::printf("  made by:   knoblab %s\n", r["tool_version"].get<std::string>().c_str());
    std::printf("  input:     SHA-256 %s of capture %lld's samples\n",
                r["input_sha256"].get<std::string>().c_str(), r["capture_id"].get<long long>());
    std::printf("  options:   %s\n", r["options"].dump().c_str());
  }
  std::printf("  result:    %s\n", one.key.c_str());
  std::printf("  files:     %zu%s\n", one.files.size(), one.files.empty() ? "" : ":");
  for (const auto& f : one.files) std::printf("    %s (%zu bytes)\n", f.name.c_str(), f.bytes.size());
}

}  // namespace

int run_results(const Args& args) {
  const bool json = args.has("json");
  if (args.positionals().empty()) {
    if (args.has("kind") || args.has("out")) throw UsageError("--kind and --out go with a result ID");
    store::Store db = open_store_to_read(args.require("db"));
    return list(db, json);
  }
  const std::int64_t id = id_arg("ID", "result", args.positionals().at(0));
  const auto kind = args.get("kind");
  if (!kind) throw UsageError("give --kind fit or --kind discrepancy: fits and discrepancy results are numbered apart");
  if (*kind != "fit" && *kind != "discrepancy")
    throw UsageError("--kind must be fit or discrepancy, got '" + *kind + "'");
  const auto out = args.get("out");
  if (out && out->empty()) throw UsageError("--out needs a directory");
  store::Store db = open_store_to_read(args.require("db"));
  const One one = load_one(db, *kind, id);
  for (const auto& f : one.files)
    if (!plain_file_name(f.name))
      throw std::runtime_error(one.name + ": refusing to write a file named '" + f.name + "'");

  if (!out) {
    if (json)
      std::printf("%s\n", one.record.dump(2).c_str());
    else
      print_one(one);
    return 0;
  }
  const std::filesystem::path dir(*out);
  std::filesystem::create_directories(dir);
  interchange::write_file_atomically(dir / "result.json", one.result + "\n");
  interchange::write_file_atomically(dir / "provenance.json", one.record.dump(2) + "\n");
  if (!one.files.empty()) write_result_files(one.files, dir / "report");
  if (!json)
    std::printf("%s: result.json, provenance.json and %zu report files (%zu bytes) written to %s\n",
                one.name.c_str(), one.files.size(), total_bytes(one.files), out->c_str());
  else
    std::printf("%s\n", one.record.dump(2).c_str());
  return 0;
}

}  // namespace knoblab::cli
