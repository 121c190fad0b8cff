// The report files stored with a result (fits, discrepancy results).
#include <string>

#include "internal.hpp"

namespace knoblab::store::detail {

namespace {

std::string in_quotes(std::string_view name) { return "'" + std::string(name) + "'"; }

std::string text(std::string_view s) { return std::string(s); }

}  // namespace

bool row_exists(sqlite::Connection& db, std::string_view table, std::int64_t id) {
  auto st = db.prepare("SELECT 1 FROM " + text(table) + " WHERE id = ?1");
  st.bind_int(1, id);
  const bool found = st.step();
  st.reset();
  return found;
}

void check_file_names(const FilesTable& t, std::span<const ResultFile> files) {
  for (const ResultFile& f : files)
    if (f.name.find('\0') != std::string::npos)
      throw StoreError(text(t.what) + " file name " + in_quotes(f.name.substr(0, f.name.find('\0'))) +
                       " is followed by a NUL byte");
}

void insert_files(sqlite::Connection& db, const FilesTable& t, std::int64_t owner,
                  std::span<const ResultFile> files) {
  auto st = db.prepare("INSERT INTO " + text(t.table) + " (" + text(t.owner_column) +
                       ", name, bytes) VALUES (?1, ?2, ?3)");
  for (const ResultFile& f : files) {
    try {
      st.bind_int(1, owner).bind_text(2, f.name).bind_blob(3, f.bytes);
      st.run();
    } catch (const StoreError& e) {
      throw StoreError(text(t.what) + " file " + in_quotes(f.name) + ": " + e.what(), e.sqlite_code());
    }
  }
}

std::vector<ResultFileInfo> list_files(sqlite::Connection& db, const FilesTable& t, std::int64_t owner) {
  std::vector<ResultFileInfo> out;
  auto st = db.prepare("SELECT name, length(bytes) FROM " + text(t.table) + " WHERE " +
                       text(t.owner_column) + " = ?1 ORDER BY name");
  st.bind_int(1, owner);
  while (st.step()) out.push_back({st.column_text(0), st.column_int(1)});
  return out;
}

std::vector<ResultFile> load_files(sqlite::Connection& db, const FilesTable& t, std::int64_t owner) {
  sqlite::Transaction tx(db, sqlite::Transaction::kRead);
  if (!row_exists(db, t.owner_table, owner))
    throw StoreError("no " + text(t.what) + " with id " + std::to_string(owner));
  std::vector<ResultFile> out;
  auto st = db.prepare("SELECT name, bytes FROM " + text(t.table) + " WHERE " + text(t.owner_column) +
                       " = ?1 ORDER BY name");
  st.bind_int(1, owner);
  while (st.step()) out.push_back({st.column_text(0), st.column_blob(1)});
  tx.commit();
  return out;
}

std::string file_count_column(const FilesTable& t) {
  return "(SELECT count(*) FROM " + text(t.table) + " f WHERE f." + text(t.owner_column) + " = " +
         text(t.owner_table) + ".id)";
}

}  // namespace knoblab::store::detail
