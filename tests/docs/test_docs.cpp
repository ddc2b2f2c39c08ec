// Issue 38 (d): the docs say true things. docs/SPEC.md is the project's specification as
// ../shared/SPEC.md holds it, byte for byte (docs/method.md links to it instead of keeping a
// copy of its own that had drifted).
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "test_util.h"

namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("docs/SPEC.md is the shared spec, unchanged", "[docs]") {
  const std::string shared = std::string(MESHSAL_SOURCE_DIR) + "/../shared/SPEC.md";
  const std::string copy = std::string(MESHSAL_SOURCE_DIR) + "/docs/SPEC.md";
  if (!meshsal_test::file_exists(shared)) {
    // No ../shared beside the tree: nothing to compare with (a skip, or a failure under
    // MESHSAL_REQUIRE_DATA=1, as for the shared meshes).
    if (meshsal_test::data_required())
      FAIL_CHECK("missing shared data " << shared << " (MESHSAL_REQUIRE_DATA=1 makes this a failure)");
    else
      meshsal_test::missing_data().push_back(shared);
    return;
  }
  const std::string want = read_all(shared), got = read_all(copy);
  if (got != want) {
    size_t at = 0;
    while (at < want.size() && at < got.size() && want[at] == got[at]) ++at;
    const size_t line = 1 + size_t(std::count(want.begin(), want.begin() + long(at), '\n'));
    FAIL("docs/SPEC.md differs from " << shared << " from line " << line
                                      << ": copy it again (cp ../shared/SPEC.md docs/SPEC.md)");
  }
}
