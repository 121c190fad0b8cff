#include "cancel.hpp"

#include <signal.h>

#include <atomic>

#include "knoblab/fit/run_hooks.hpp"

namespace knoblab::cli {

namespace {

// Lock-free, so the handler may set it (async-signal-safe).
std::atomic<bool> g_cancelled{false};
static_assert(std::atomic<bool>::is_always_lock_free);

struct sigaction g_old_int, g_old_term;

extern "C" void on_cancel_signal(int) { g_cancelled.store(true, std::memory_order_relaxed); }

}  // namespace

CancelOnSignal::CancelOnSignal() {
  g_cancelled = false;
  struct sigaction sa {};
  sa.sa_handler = on_cancel_signal;
  sigemptyset(&sa.sa_mask);
  // SA_RESTART: a read or write the signal interrupts goes on (sqlite, file
  // writes); SA_RESETHAND: the second Ctrl-C is the default one.
  sa.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(SIGINT, &sa, &g_old_int);
  sigaction(SIGTERM, &sa, &g_old_term);
}

CancelOnSignal::~CancelOnSignal() {
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
}

bool cancel_requested() { return g_cancelled.load(std::memory_order_relaxed); }

void throw_if_cancelled() {
  if (cancel_requested()) throw fit::Cancelled();
}

}  // namespace knoblab::cli
