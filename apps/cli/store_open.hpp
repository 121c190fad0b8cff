// How commands open --db. Reading commands (list, export, inspect, fits,
// fit-export) open it read-only: they never write, so they never wait for
// hapticd's lock. Commands that add results to a stored capture (fit,
// discrepancy) write. Neither creates a store: a mistyped path is an error,
// not a new empty store. Only import, simulate and demo create one.
#pragma once

#include <string>

#include "knoblab/store/store.hpp"

namespace knoblab::cli {

store::Store open_store_to_read(const std::string& path);
store::Store open_store_to_add(const std::string& path);

}  // namespace knoblab::cli
