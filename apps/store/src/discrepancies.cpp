// Discrepancy results, kept beside their capture with their provenance and
// report files.
#include <string>

#include "internal.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::store {

namespace {

using detail::kDiscrepancyFiles;

std::string discrepancy_select() {
  return "SELECT id, capture_id, heldout_capture_id, result, created_at, " +
         std::string(detail::kProvenanceColumns) + ", " + detail::file_count_column(kDiscrepancyFiles) +
         " FROM discrepancies";
}

DiscrepancyInfo read_discrepancy_row(const sqlite::Statement& st) {
  DiscrepancyInfo d;
  d.id = st.column_int(0);
  d.capture_id = st.column_int(1);
  if (!st.is_null(2)) d.heldout_capture_id = st.column_int(2);
  d.result = st.column_text(3);
  d.created_at = st.column_text(4);
  d.provenance = detail::read_provenance(st, 5);
  d.file_count = st.column_int(8);
  return d;
}

}  // namespace

std::int64_t Store::insert_discrepancy(std::int64_t capture_id, std::string_view result_json,
                                       std::optional<std::int64_t> heldout_capture_id,
                                       std::span<const ResultFile> files,
                                       const std::optional<Provenance>& provenance) {
  detail::check_file_names(kDiscrepancyFiles, files);
  if (provenance) detail::check_provenance(*db_, *provenance, "discrepancy");
  sqlite::Transaction tx(*db_);
  // The schema refuses these too, but its "FOREIGN KEY constraint failed"
  // does not say which id; checked under the write lock, so the answer holds
  // for the insert.
  if (!detail::row_exists(*db_, "captures", capture_id))
    throw StoreError("no capture with id " + std::to_string(capture_id));
  if (heldout_capture_id && !detail::row_exists(*db_, "captures", *heldout_capture_id))
    throw StoreError("no held-out capture with id " + std::to_string(*heldout_capture_id));
  auto valid = db_->prepare("SELECT json_valid(?1)");
  valid.bind_text(1, result_json);
  if (!valid.step() || valid.column_int(0) != 1)
    throw StoreError("discrepancy result of capture " + std::to_string(capture_id) +
                     " is not valid JSON");
  valid.reset();
  auto st = db_->prepare(
      "INSERT INTO discrepancies (capture_id, heldout_capture_id, result, tool_version,"
      " input_sha256, options) VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
  st.bind_int(1, capture_id);
  if (heldout_capture_id)
    st.bind_int(2, *heldout_capture_id);
  else
    st.bind_null(2);
  st.bind_text(3, result_json);
  detail::bind_provenance(st, 4, provenance);
  st.run();
  const std::int64_t id = db_->last_insert_rowid();
  detail::insert_files(*db_, kDiscrepancyFiles, id, files);
  tx.commit();
  return id;
}

std::vector<DiscrepancyInfo> Store::list_discrepancies(std::int64_t capture_id) {
  std::vector<DiscrepancyInfo> out;
  auto st = db_->prepare(discrepancy_select() + " WHERE capture_id = ?1 ORDER BY id");
  st.bind_int(1, capture_id);
  while (st.step()) out.push_back(read_discrepancy_row(st));
  return out;
}

std::vector<DiscrepancyInfo> Store::list_all_discrepancies() {
  std::vector<DiscrepancyInfo> out;
  auto st = db_->prepare(discrepancy_select() + " ORDER BY id");
  while (st.step()) out.push_back(read_discrepancy_row(st));
  return out;
}

std::optional<DiscrepancyInfo> Store::discrepancy_info(std::int64_t id) {
  auto st = db_->prepare(discrepancy_select() + " WHERE id = ?1");
  st.bind_int(1, id);
  if (!st.step()) return std::nullopt;
  auto info = read_discrepancy_row(st);
  st.reset();
  return info;
}

std::vector<ResultFileInfo> Store::list_discrepancy_files(std::int64_t id) {
  return detail::list_files(*db_, kDiscrepancyFiles, id);
}

std::vector<ResultFile> Store::load_discrepancy_files(std::int64_t id) {
  return detail::load_files(*db_, kDiscrepancyFiles, id);
}

}  // namespace knoblab::store
