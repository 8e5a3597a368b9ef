// For the Qt tests that run under gtest: a wait whose failure gtest sees. (QtTest's QTRY_*
// report to QtTest, whose failures a gtest test never hears of: it only ends early.)
#pragma once

#include <QElapsedTimer>
#include <QTest>

namespace hdrf::test {

// Processes events until `done` holds (true) or `ms` pass (false).
template <typename F>
bool WaitUntil(F done, int ms) {
  QElapsedTimer t;
  t.start();
  while (!done()) {
    if (t.elapsed() > ms) return false;
    QTest::qWait(20);
  }
  return true;
}

}  // namespace hdrf::test
