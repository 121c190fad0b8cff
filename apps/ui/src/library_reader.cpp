#include "library_reader.hpp"

#include <algorithm>
#include <stdexcept>

#include "knoblab/store/store.hpp"

namespace knoblab::ui {

namespace {

nlohmann::json parsed(const std::string& text) {
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  return j.is_discarded() ? nlohmann::json() : j;
}

// The store opened for reading only: it never writes, never waits for a writer.
store::Store open_read_only(const std::filesystem::path& db) {
  store::OpenOptions o;
  o.read_only = true;
  return store::Store::open(db, o);
}

}  // namespace

std::vector<LibraryEntry> read_library(const std::filesystem::path& db) {
  std::vector<LibraryEntry> out;
  if (!std::filesystem::exists(db)) return out;
  try {
    store::Store s = open_read_only(db);
    const auto fits = s.list_all_fits();
    const auto results = s.list_all_discrepancies();
    for (const store::CaptureInfo& c : s.list_captures()) {
      LibraryEntry e;
      e.capture_id = c.id;
      e.knob = c.knob;
      e.status = c.status;
      e.started_at = c.started_at;
      e.stimulus = c.stimulus;
      e.orientation = c.orientation;
      e.end_reason = c.end_reason.value_or("");
      e.mounting = c.mode;
      const nlohmann::json meta = parsed(c.metadata);
      if (meta.is_object()) e.metadata = meta;
      e.rate_hz = c.rate_hz;
      e.samples = c.sample_count;
      // Both lists are by id: the last one of this capture is the latest,
      // the only one whose result is parsed.
      const store::FitInfo* fit = nullptr;
      for (const store::FitInfo& f : fits)
        if (f.capture_id == c.id) fit = &f;
      if (fit) e.fit_id = fit->id, e.fit = parsed(fit->result);
      const store::DiscrepancyInfo* result = nullptr;
      for (const store::DiscrepancyInfo& d : results)
        if (d.capture_id == c.id) result = &d;
      if (result) e.discrepancy_id = result->id, e.discrepancy = parsed(result->result);
      out.push_back(std::move(e));
    }
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot read the knob library " + db.string() + ": " + e.what());
  }
  std::reverse(out.begin(), out.end());
  return out;
}

std::string read_result_file(const std::filesystem::path& db, const std::string& kind, std::int64_t id,
                             const std::string& name) {
  if (!std::filesystem::exists(db)) return {};
  try {
    store::Store s = open_read_only(db);
    if (kind == "fit") {
      for (const store::FitFileInfo& f : s.list_fit_files(id))
        if (f.name == name) {
          const std::vector<std::uint8_t> bytes = s.load_fit_file(id, name);
          return {bytes.begin(), bytes.end()};
        }
      return {};
    }
    for (const store::ResultFile& f : s.load_discrepancy_files(id))
      if (f.name == name) return {f.bytes.begin(), f.bytes.end()};
    return {};
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot read " + name + " of " + kind + " " + std::to_string(id) + ": " + e.what());
  }
}

nlohmann::json entry_json(const LibraryEntry& e) {
  nlohmann::json j = {{"capture_id", e.capture_id}, {"knob", e.knob},         {"status", e.status},
                      {"started_at", e.started_at}, {"stimulus", e.stimulus}, {"orientation", e.orientation},
                      {"end_reason", e.end_reason}, {"rate_hz", e.rate_hz},   {"samples", e.samples},
                      {"mounting", e.mounting},     {"gripper", e.metadata.value("gripper", "")},
                      {"notes", e.metadata.value("notes", "")}};
  j["fit"] = nullptr;
  if (e.fit_id && e.fit.is_object()) {
    nlohmann::json params = nlohmann::json::array();
    const nlohmann::json ci = e.fit.value("ci95", nlohmann::json::object());
    const nlohmann::json fitted = e.fit.value("params", nlohmann::json::object());
    for (const auto& [name, value] : fitted.items()) {
      nlohmann::json p = {{"name", name}, {"value", value}};
      if (ci.contains(name) && ci[name].is_array() && ci[name].size() == 2) p["ci95"] = ci[name];
      params.push_back(p);
    }
    j["fit"] = {{"id", *e.fit_id},
                {"params", params},
                {"rmse_Nm", e.fit.value("rmse_Nm", 0.0)},
                {"fit_percent", e.fit.value("fit_percent", 0.0)},
                {"detents", e.fit.value("detents", nlohmann::json::object())},
                {"stick", e.fit.value("stick", nlohmann::json())}};
  }
  j["discrepancy"] = nullptr;
  if (e.discrepancy_id && e.discrepancy.is_object()) {
    const auto findings = [&](const char* key) {
      nlohmann::json out = nlohmann::json::array();
      const nlohmann::json listed = e.discrepancy.value(key, nlohmann::json::array());
      for (const nlohmann::json& f : listed)
        out.push_back({{"effect", f.value("effect", "")},
                       {"confidence", f.value("confidence", 0.0)},
                       {"where", f.value("where", "")},
                       {"explanation", f.value("explanation", "")}});
      return out;
    };
    const nlohmann::json base = e.discrepancy.value("base", nlohmann::json::object());
    const nlohmann::json final_model = e.discrepancy.value("final", nlohmann::json::object());
    j["discrepancy"] = {{"id", *e.discrepancy_id},
                        {"findings", findings("findings")},
                        {"tentative", findings("tentative_findings")},
                        {"base_heldout_rmse_Nm", base.value("heldout_rmse_Nm", 0.0)},
                        {"final_heldout_rmse_Nm", final_model.value("heldout_rmse_Nm", 0.0)}};
  }
  return j;
}

}  // namespace knoblab::ui
