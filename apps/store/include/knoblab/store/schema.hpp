// Schema versions: an ordered list of migration steps, tracked in
// PRAGMA user_version. Store::open migrates to the latest version.
#pragma once

#include "knoblab/store/sqlite.hpp"

namespace knoblab::store {

// The version a fresh database gets; the number of migration steps.
int latest_schema_version();

// PRAGMA user_version of an open database.
int schema_version(sqlite::Connection& db);

// Throws StoreError if `version` is newer than latest_schema_version().
void check_schema_not_newer(int version);

// Applies the missing steps up to `target` (each in its own transaction, so a
// failing step leaves the database at the previous version). Refuses, with a
// StoreError, a database newer than this binary knows. Safe against another
// process migrating at the same time: each step rechecks the version under
// the write lock.
void migrate(sqlite::Connection& db, int target = latest_schema_version());

}  // namespace knoblab::store
