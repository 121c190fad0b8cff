// Ctrl-C (SIGINT) and SIGTERM during a long command (fit, discrepancy,
// simulate, import). While a CancelOnSignal lives, the first such signal
// only sets a flag, which the command polls between steps (its
// fit::RunHooks::cancelled, the Ceres iterations, between simulation chunks
// and import transactions): the command stops before it writes anything,
// removes what it had begun in the store, and main exits 130 saying
// "cancelled". The handler goes back to the default action as it runs
// (SA_RESETHAND), so a second signal ends the process at once; even then
// the store's transactions and the result files' renames are never half
// done.
#pragma once

namespace knoblab::cli {

class CancelOnSignal {
 public:
  CancelOnSignal();   // installs the handlers, clears the flag
  ~CancelOnSignal();  // puts back what was there
  CancelOnSignal(const CancelOnSignal&) = delete;
  CancelOnSignal& operator=(const CancelOnSignal&) = delete;
};

// Whether SIGINT or SIGTERM came while a CancelOnSignal lived.
bool cancel_requested();
// Throws fit::Cancelled when cancel_requested().
void throw_if_cancelled();

}  // namespace knoblab::cli
