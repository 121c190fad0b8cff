// Helpers shared by the store's source files; not part of the API.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "knoblab/store/sqlite.hpp"
#include "knoblab/store/types.hpp"

namespace knoblab::store::detail {

// process.cpp
bool process_alive(std::int64_t pid);  // kill(pid, 0) does not say ESRCH
std::string boot_id();                 // this boot's id, "" if unknown

// store.cpp: call inside a write transaction. `created` (when given) tells
// whether the knob was inserted just now.
std::optional<std::int64_t> resolve_knob(sqlite::Connection& db, std::string_view name,
                                         std::string_view description = {},
                                         bool* created = nullptr);
// Inserts the captures row; recording rows carry our pid and boot id.
std::int64_t insert_capture_row(sqlite::Connection& db, const NewCapture& info,
                                std::string_view status, bool has_command,
                                bool* created_knob = nullptr);

// store.cpp: deletes a capture that never got finished (samples cascade)
// and the knob made for it when nothing else uses it, in one transaction.
void remove_unfinished_capture(sqlite::Connection& db, std::int64_t id,
                               std::optional<std::int64_t> created_knob);
// store.cpp: Store::delete_capture inside the caller's write transaction:
// the capture with everything that cascades from it. Refuses (StoreError)
// an unknown capture and one still 'recording'.
void delete_capture_row(sqlite::Connection& db, std::int64_t id);
// The knob a capture row refers to, if any.
std::optional<std::int64_t> knob_of_capture(sqlite::Connection& db, std::int64_t id);

// load.cpp: SELECT list matching read_capture_row, for "FROM captures c".
extern const char* const kCaptureColumns;
CaptureInfo read_capture_row(const sqlite::Statement& st);

// Whether a row with this id is in `table` (one of ours, never user text).
bool row_exists(sqlite::Connection& db, std::string_view table, std::int64_t id);

// result_files.cpp: the report files stored with a result, one table per
// kind of result (fit_files, discrepancy_files), all alike.
struct FilesTable {
  std::string_view table;         // fit_files
  std::string_view owner_column;  // fit_id
  std::string_view owner_table;   // fits
  std::string_view what;          // "fit", in messages
};
inline constexpr FilesTable kFitFiles{"fit_files", "fit_id", "fits", "fit"};
inline constexpr FilesTable kDiscrepancyFiles{"discrepancy_files", "discrepancy_id", "discrepancies",
                                              "discrepancy"};
// Before any write: a NUL would hide the rest of a name from the schema's CHECK.
void check_file_names(const FilesTable& t, std::span<const ResultFile> files);
// Inside the caller's write transaction, with the owner's row.
void insert_files(sqlite::Connection& db, const FilesTable& t, std::int64_t owner,
                  std::span<const ResultFile> files);
std::vector<ResultFileInfo> list_files(sqlite::Connection& db, const FilesTable& t, std::int64_t owner);
// From one snapshot; throws StoreError for an unknown owner.
std::vector<ResultFile> load_files(sqlite::Connection& db, const FilesTable& t, std::int64_t owner);
// "(SELECT count(*) …)": the owner's file count, for "FROM <owner_table>".
std::string file_count_column(const FilesTable& t);

// provenance.cpp: the columns schema 7 added to fits and discrepancies.
inline constexpr std::string_view kProvenanceColumns = "tool_version, input_sha256, options";
// Throws StoreError saying which field is wrong (`what`: "fit").
void check_provenance(sqlite::Connection& db, const Provenance& p, std::string_view what);
// Binds the three columns at first, first + 1, first + 2 (NULL for none).
void bind_provenance(sqlite::Statement& st, int first, const std::optional<Provenance>& p);
std::optional<Provenance> read_provenance(const sqlite::Statement& st, int first);

}  // namespace knoblab::store::detail
