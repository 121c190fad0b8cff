// Fits and their report files.
#include <string>

#include "knoblab/store/store.hpp"

namespace knoblab::store {

namespace {

constexpr const char* kFitColumns = "SELECT id, capture_id, model, params, result, created_at FROM fits";

FitInfo read_fit_row(const sqlite::Statement& st) {
  return {st.column_int(0), st.column_int(1), st.column_text(2),
          st.column_text(3), st.column_text(4), st.column_text(5)};
}

std::string in_quotes(std::string_view name) { return "'" + std::string(name) + "'"; }

bool fit_exists(sqlite::Connection& db, std::int64_t fit_id) {
  auto st = db.prepare("SELECT 1 FROM fits WHERE id = ?1");
  st.bind_int(1, fit_id);
  const bool found = st.step();
  st.reset();
  return found;
}

}  // namespace

std::int64_t Store::insert_fit(std::int64_t capture_id, std::string_view model,
                               std::string_view params_json, std::string_view result_json,
                               std::span<const FitFile> files) {
  // The schema checks the rest; a NUL would hide the part of a name after it
  // from its CHECK (sqlite's string functions stop there).
  for (const FitFile& f : files)
    if (f.name.find('\0') != std::string::npos)
      throw StoreError("fit file name " + in_quotes(f.name.substr(0, f.name.find('\0'))) +
                       " is followed by a NUL byte");
  sqlite::Transaction tx(*db_);
  db_->prepare("INSERT INTO fits (capture_id, model, params, result) VALUES (?1, ?2, ?3, ?4)")
      .bind_int(1, capture_id)
      .bind_text(2, model)
      .bind_text(3, params_json)
      .bind_text(4, result_json)
      .run();
  const std::int64_t id = db_->last_insert_rowid();
  auto st = db_->prepare("INSERT INTO fit_files (fit_id, name, bytes) VALUES (?1, ?2, ?3)");
  for (const FitFile& f : files) {
    try {
      st.bind_int(1, id).bind_text(2, f.name).bind_blob(3, f.bytes);
      st.run();
    } catch (const StoreError& e) {
      throw StoreError("fit file " + in_quotes(f.name) + ": " + e.what(), e.sqlite_code());
    }
  }
  tx.commit();
  return id;
}

std::vector<FitInfo> Store::list_fits(std::int64_t capture_id) {
  std::vector<FitInfo> fits;
  auto st = db_->prepare(std::string(kFitColumns) + " WHERE capture_id = ?1 ORDER BY id");
  st.bind_int(1, capture_id);
  while (st.step()) fits.push_back(read_fit_row(st));
  return fits;
}

std::vector<FitInfo> Store::list_all_fits() {
  std::vector<FitInfo> fits;
  auto st = db_->prepare(std::string(kFitColumns) + " ORDER BY id");
  while (st.step()) fits.push_back(read_fit_row(st));
  return fits;
}

std::optional<FitInfo> Store::fit_info(std::int64_t fit_id) {
  auto st = db_->prepare(std::string(kFitColumns) + " WHERE id = ?1");
  st.bind_int(1, fit_id);
  if (!st.step()) return std::nullopt;
  auto info = read_fit_row(st);
  st.reset();
  return info;
}

std::vector<FitFileInfo> Store::list_fit_files(std::int64_t fit_id) {
  std::vector<FitFileInfo> out;
  auto st = db_->prepare(
      "SELECT name, length(bytes) FROM fit_files WHERE fit_id = ?1 ORDER BY name");
  st.bind_int(1, fit_id);
  while (st.step()) out.push_back({st.column_text(0), st.column_int(1)});
  return out;
}

std::vector<std::uint8_t> Store::load_fit_file(std::int64_t fit_id, std::string_view name) {
  sqlite::Transaction tx(*db_, sqlite::Transaction::kRead);
  auto st = db_->prepare("SELECT bytes FROM fit_files WHERE fit_id = ?1 AND name = ?2");
  st.bind_int(1, fit_id).bind_text(2, name);
  if (!st.step()) {
    if (!fit_exists(*db_, fit_id)) throw StoreError("no fit with id " + std::to_string(fit_id));
    throw StoreError("fit " + std::to_string(fit_id) + " has no file " + in_quotes(name));
  }
  auto bytes = st.column_blob(0);
  st.reset();
  tx.commit();
  return bytes;
}

std::vector<FitFile> Store::load_fit_files(std::int64_t fit_id) {
  sqlite::Transaction tx(*db_, sqlite::Transaction::kRead);
  if (!fit_exists(*db_, fit_id)) throw StoreError("no fit with id " + std::to_string(fit_id));
  std::vector<FitFile> out;
  auto st = db_->prepare("SELECT name, bytes FROM fit_files WHERE fit_id = ?1 ORDER BY name");
  st.bind_int(1, fit_id);
  while (st.step()) out.push_back({st.column_text(0), st.column_blob(1)});
  tx.commit();
  return out;
}

}  // namespace knoblab::store
