// Fits, their provenance and their report files.
#include <string>

#include "internal.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::store {

namespace {

using detail::kFitFiles;

std::string fit_select() {
  return "SELECT id, capture_id, model, params, result, created_at, " +
         std::string(detail::kProvenanceColumns) + ", " + detail::file_count_column(kFitFiles) +
         " FROM fits";
}

FitInfo read_fit_row(const sqlite::Statement& st) {
  FitInfo f;
  f.id = st.column_int(0);
  f.capture_id = st.column_int(1);
  f.model = st.column_text(2);
  f.params = st.column_text(3);
  f.result = st.column_text(4);
  f.created_at = st.column_text(5);
  f.provenance = detail::read_provenance(st, 6);
  f.file_count = st.column_int(9);
  return f;
}

std::string in_quotes(std::string_view name) { return "'" + std::string(name) + "'"; }

}  // namespace

std::int64_t Store::insert_fit(std::int64_t capture_id, std::string_view model,
                               std::string_view params_json, std::string_view result_json,
                               std::span<const FitFile> files,
                               const std::optional<Provenance>& provenance) {
  detail::check_file_names(kFitFiles, files);
  if (provenance) detail::check_provenance(*db_, *provenance, "fit");
  sqlite::Transaction tx(*db_);
  auto st = db_->prepare(
      "INSERT INTO fits (capture_id, model, params, result, tool_version, input_sha256, options)"
      " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)");
  st.bind_int(1, capture_id).bind_text(2, model).bind_text(3, params_json).bind_text(4, result_json);
  detail::bind_provenance(st, 5, provenance);
  st.run();
  const std::int64_t id = db_->last_insert_rowid();
  detail::insert_files(*db_, kFitFiles, id, files);
  tx.commit();
  return id;
}

std::vector<FitInfo> Store::list_fits(std::int64_t capture_id) {
  std::vector<FitInfo> fits;
  auto st = db_->prepare(fit_select() + " WHERE capture_id = ?1 ORDER BY id");
  st.bind_int(1, capture_id);
  while (st.step()) fits.push_back(read_fit_row(st));
  return fits;
}

std::vector<FitInfo> Store::list_all_fits() {
  std::vector<FitInfo> fits;
  auto st = db_->prepare(fit_select() + " ORDER BY id");
  while (st.step()) fits.push_back(read_fit_row(st));
  return fits;
}

std::optional<FitInfo> Store::fit_info(std::int64_t fit_id) {
  auto st = db_->prepare(fit_select() + " WHERE id = ?1");
  st.bind_int(1, fit_id);
  if (!st.step()) return std::nullopt;
  auto info = read_fit_row(st);
  st.reset();
  return info;
}

std::vector<FitFileInfo> Store::list_fit_files(std::int64_t fit_id) {
  return detail::list_files(*db_, kFitFiles, fit_id);
}

std::vector<std::uint8_t> Store::load_fit_file(std::int64_t fit_id, std::string_view name) {
  sqlite::Transaction tx(*db_, sqlite::Transaction::kRead);
  auto st = db_->prepare("SELECT bytes FROM fit_files WHERE fit_id = ?1 AND name = ?2");
  st.bind_int(1, fit_id).bind_text(2, name);
  if (!st.step()) {
    if (!detail::row_exists(*db_, "fits", fit_id))
      throw StoreError("no fit with id " + std::to_string(fit_id));
    throw StoreError("fit " + std::to_string(fit_id) + " has no file " + in_quotes(name));
  }
  auto bytes = st.column_blob(0);
  st.reset();
  tx.commit();
  return bytes;
}

std::vector<FitFile> Store::load_fit_files(std::int64_t fit_id) {
  return detail::load_files(*db_, kFitFiles, fit_id);
}

}  // namespace knoblab::store
