// The one Catch2 main for all test files.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>

#include <iostream>

#include "test_util.h"

namespace {

// Reports the shared meshes a test case found missing (meshsal_test::shared_mesh), and what it
// could not run here (meshsal_test::skip_case): one "SKIPPED: missing shared data <path>" or
// "SKIPPED: not run here: <reason>" line each when the case had no failure, which ctest
// turns into a skipped test (SKIP_REGULAR_EXPRESSION in CMakeLists.txt). A case that also
// failed says so without the SKIPPED line, so a skip never hides a failure.
struct MissingDataListener : Catch::TestEventListenerBase {
  using TestEventListenerBase::TestEventListenerBase;
  void testCaseStarting(const Catch::TestCaseInfo& info) override {
    TestEventListenerBase::testCaseStarting(info);
    meshsal_test::missing_data().clear();
    meshsal_test::skip_reasons().clear();
  }
  void testCaseEnded(const Catch::TestCaseStats& stats) override {
    const bool failed = stats.totals.assertions.failed > 0;
    for (const std::string& path : meshsal_test::missing_data())
      std::cout << (failed ? "not run (and the test failed): missing shared data " : "SKIPPED: missing shared data ")
                << path << " (test case \"" << stats.testInfo.name << "\")\n";
    for (const std::string& reason : meshsal_test::skip_reasons())
      std::cout << (failed ? "not run (and the test failed): " : "SKIPPED: not run here: ") << reason
                << " (test case \"" << stats.testInfo.name << "\")\n";
    std::cout.flush();
    meshsal_test::missing_data().clear();
    meshsal_test::skip_reasons().clear();
    TestEventListenerBase::testCaseEnded(stats);
  }
};

}  // namespace

CATCH_REGISTER_LISTENER(MissingDataListener)
