// Waiting in a UI test: Qt's event loop runs (queued signals from the link's
// thread, the library's reads, QML bindings) until what the test waits for
// holds. The deadline only bounds the wait; nothing asserts how long it took.
#pragma once

#include <QCoreApplication>
#include <QElapsedTimer>

#include <functional>

namespace knoblab::ui::test_loop {

// Runs the event loop until `done` holds (true) or `ms` pass (false).
inline bool spin_until(const std::function<bool()>& done, int ms = 60000) {
  QElapsedTimer t;
  t.start();
  while (!done()) {
    if (t.elapsed() > ms) return false;
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  }
  return true;
}

// Runs the event loop for `ms`.
inline void run_for(int ms) {
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < ms) QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
}

}  // namespace knoblab::ui::test_loop
