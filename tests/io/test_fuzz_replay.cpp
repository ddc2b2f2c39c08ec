// [fuzz] The fuzz targets' inputs replayed in the normal suite (tools/fuzz.sh runs the
// fuzzers themselves): every seed in tests/fuzz/corpus loads (rows: parses and joins), and
// every file in tests/fuzz/regressions (hostile inputs and what the fuzzers found) gives
// exactly the outcome tests/fuzz/regressions/expected.txt records, without crashing.
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <catch2/catch.hpp>

#include "fuzz/fuzz_load.h"

namespace fs = std::filesystem;

namespace {

const fs::path kFuzzDir = MESHSAL_FUZZ_DIR;

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string replay(const std::string& target, const fs::path& file) {
  const std::string bytes = read_all(file);
  return meshsal_fuzz::run_target(target, reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

// "TARGET/NAME" -> expected fragment ("loads" for none).
std::map<std::string, std::string> expected_outcomes() {
  std::map<std::string, std::string> out;
  std::ifstream in(kFuzzDir / "regressions" / "expected.txt");
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const size_t colon = line.find(": ");
    if (colon != std::string::npos) out[line.substr(0, colon)] = line.substr(colon + 2);
  }
  return out;
}

}  // namespace

TEST_CASE("fuzz corpus: every seed loads", "[fuzz]") {
  size_t files = 0;
  for (const char* target : {"obj", "off", "ply", "stl", "gltf", "glb", "gz", "saliency", "plystream", "rows"}) {
    for (const auto& entry : fs::directory_iterator(kFuzzDir / "corpus" / target)) {
      INFO(target << ": " << entry.path().filename().string());
      CHECK(replay(target, entry.path()) == "");
      ++files;
    }
  }
  CHECK(files >= 10);
}

TEST_CASE("fuzz regressions: each file gives its recorded outcome", "[fuzz]") {
  const auto expected = expected_outcomes();
  REQUIRE(expected.size() >= 10);
  size_t files = 0;
  for (const char* target : {"obj", "off", "ply", "stl", "gltf", "glb", "gz", "saliency", "plystream", "rows"}) {
    const fs::path dir = kFuzzDir / "regressions" / target;
    if (!fs::exists(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string key = std::string(target) + "/" + entry.path().filename().string();
      INFO(key);
      const auto it = expected.find(key);
      if (it == expected.end()) FAIL("not listed in tests/fuzz/regressions/expected.txt");
      const std::string outcome = replay(target, entry.path());
      INFO("outcome: " << outcome);
      if (it->second == "loads") {
        CHECK(outcome == "");
      } else {
        CHECK(outcome.rfind("fuzz.", 0) == 0);  // the message names the input
        CHECK(outcome.find('\n') == std::string::npos);
        CHECK(outcome.find(it->second) != std::string::npos);
      }
      ++files;
    }
  }
  CHECK(files == expected.size());
}
