// The one exception type of the store.
#pragma once

#include <stdexcept>
#include <string>

namespace knoblab::store {

class StoreError : public std::runtime_error {
 public:
  explicit StoreError(const std::string& what, int sqlite_code = 0)
      : std::runtime_error(what), sqlite_code_(sqlite_code) {}

  // sqlite's extended result code (e.g. SQLITE_CONSTRAINT_CHECK), 0 when the
  // error was detected by knoblab itself.
  int sqlite_code() const { return sqlite_code_; }

 private:
  int sqlite_code_;
};

}  // namespace knoblab::store
