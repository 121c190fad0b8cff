#include "result_view.hpp"

#include <cstdio>

#include "args.hpp"

namespace knoblab::cli {

namespace {

nlohmann::json parsed(const std::string& text) {
  return nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
}

nlohmann::json number_or_null(std::optional<double> v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

// The fields every result's record has.
nlohmann::json record(const char* kind, std::int64_t id, std::int64_t capture_id, const std::string& created_at,
                      const std::optional<store::Provenance>& p, std::int64_t files) {
  nlohmann::json j;
  j["kind"] = kind;
  j["id"] = id;
  j["capture_id"] = capture_id;
  j["created_at"] = created_at;
  j["tool_version"] = p ? nlohmann::json(p->tool_version) : nlohmann::json(nullptr);
  j["input_sha256"] = p ? nlohmann::json(p->input_sha256) : nlohmann::json(nullptr);
  j["options"] = p ? parsed(p->options) : nlohmann::json(nullptr);
  j["files"] = files;
  return j;
}

}  // namespace

std::int64_t id_arg(const std::string& what, const std::string& noun, const std::string& text) {
  return parse_id(what, text, noun);
}

std::optional<double> number_at(const nlohmann::json& result, std::initializer_list<const char*> keys) {
  const nlohmann::json* j = &result;
  for (const char* key : keys) {
    if (!j->is_object()) return std::nullopt;
    const auto it = j->find(key);
    if (it == j->end()) return std::nullopt;
    j = &*it;
  }
  if (!j->is_number()) return std::nullopt;
  return j->get<double>();
}

std::string figure(std::optional<double> v, int precision, bool fixed) {
  if (!v) return "-";
  char buf[64];
  if (fixed)
    std::snprintf(buf, sizeof buf, "%.*f", precision, *v);
  else
    std::snprintf(buf, sizeof buf, "%.*g", precision, *v);
  return buf;
}

std::string version_of(const std::optional<store::Provenance>& p) { return p ? p->tool_version : "-"; }

std::string short_sha256(const std::optional<store::Provenance>& p) {
  return p ? p->input_sha256.substr(0, 12) : "-";
}

std::string fit_key_figure(const store::FitInfo& f) {
  const nlohmann::json r = parsed(f.result);
  const auto rmse = number_at(r, {"rmse_Nm"});
  std::string out = "rmse " + (rmse ? figure(*rmse * 1e3, 4, false) + " mN·m" : std::string("-"));
  if (const auto per_rev = number_at(r, {"detents", "per_rev"})) out += ", " + figure(per_rev, 2, true) + " detents/rev";
  return out;
}

std::string discrepancy_key_figure(const store::DiscrepancyInfo& d) {
  const nlohmann::json r = parsed(d.result);
  const auto base = number_at(r, {"base", "heldout_rmse_Nm"});
  const auto final_rmse = number_at(r, {"final", "heldout_rmse_Nm"});
  const auto milli = [](std::optional<double> v) { return v ? figure(*v * 1e3, 3, false) : std::string("-"); };
  std::string out = "held-out rms " + milli(base) + " → " + milli(final_rmse) + " mN·m";
  const auto findings = r.is_object() ? r.find("findings") : r.end();
  if (r.is_object() && findings != r.end() && findings->is_array()) {
    const std::size_t n = findings->size();
    out += n == 0 ? ", no finding" : ", " + std::to_string(n) + (n == 1 ? " finding" : " findings");
  }
  return out;
}

nlohmann::json fit_record(const store::FitInfo& f) {
  nlohmann::json j = record("fit", f.id, f.capture_id, f.created_at, f.provenance, f.file_count);
  const nlohmann::json r = parsed(f.result);
  j["model"] = f.model;
  j["key"] = {{"rmse_Nm", number_or_null(number_at(r, {"rmse_Nm"}))},
              {"detents_per_rev", number_or_null(number_at(r, {"detents", "per_rev"}))}};
  return j;
}

nlohmann::json discrepancy_record(const store::DiscrepancyInfo& d) {
  nlohmann::json j = record("discrepancy", d.id, d.capture_id, d.created_at, d.provenance, d.file_count);
  const nlohmann::json r = parsed(d.result);
  j["heldout_capture_id"] = d.heldout_capture_id ? nlohmann::json(*d.heldout_capture_id) : nlohmann::json(nullptr);
  const auto findings = r.is_object() ? r.find("findings") : r.end();
  j["key"] = {{"base_heldout_rmse_Nm", number_or_null(number_at(r, {"base", "heldout_rmse_Nm"}))},
              {"final_heldout_rmse_Nm", number_or_null(number_at(r, {"final", "heldout_rmse_Nm"}))},
              {"findings", r.is_object() && findings != r.end() && findings->is_array()
                               ? nlohmann::json(findings->size())
                               : nlohmann::json(nullptr)}};
  return j;
}

}  // namespace knoblab::cli
