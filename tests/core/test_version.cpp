// Issue 22 (5): one version, CMake's project(VERSION): the public header, `meshsal --version`
// and the Python module (tests/python/test_version.py) say the same.
#include <catch2/catch.hpp>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "cli_run.h"
#include "meshsal/meshsal.h"

namespace {

std::string project_version() {
  std::ifstream f(std::string(MESHSAL_SOURCE_DIR) + "/CMakeLists.txt");
  std::stringstream ss;
  ss << f.rdbuf();
  std::smatch m;
  const std::string text = ss.str();
  REQUIRE(std::regex_search(text, m, std::regex("project\\(meshsal VERSION ([0-9]+)\\.([0-9]+)\\.([0-9]+)")));
  return m[1].str() + "." + m[2].str() + "." + m[3].str();
}

}  // namespace

TEST_CASE("version: the header and meshsal --version give CMake's project version", "[cli]") {
  const std::string v = project_version();
  CHECK(std::string(MESHSAL_VERSION_STRING) == v);
  const int major = std::stoi(v.substr(0, v.find('.')));
  const int minor = std::stoi(v.substr(v.find('.') + 1));
  const int patch = std::stoi(v.substr(v.rfind('.') + 1));
  CHECK(MESHSAL_VERSION == major * 10000 + minor * 100 + patch);
  const meshsal_test::CliRun r = meshsal_test::run_cli("--version");
  CHECK(r.rc == 0);
  CHECK(r.out == "meshsal " + v + "\n");
}
