// What every PLplot report in the process shares: PLplot keeps global state,
// so one lock serialises all of them (the fit report and the discrepancy
// report alike), and one rule for showing text as written.
#pragma once

#include <mutex>
#include <string>

namespace knoblab::fit {

// Held while a PLplot stream is open, by every report.
std::mutex& plplot_mutex();

// PLplot's escape character '#' doubled, so text is shown as written.
std::string plplot_escape(const std::string& s);

}  // namespace knoblab::fit
