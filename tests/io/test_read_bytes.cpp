// read_file: a large regular file read in ranges on every core gives its bytes as they are.
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "cli_run.h"
#include "io/read_bytes.h"
#include "test_util.h"

using namespace meshsal;

TEST_CASE("read_file: a file over the ranged read's threshold, read whole and in order", "[io]") {
  const std::filesystem::path dir = meshsal_test::scratch_dir("read_bytes");
  const std::string path = (dir / "big.bin").string();
  // 70 MiB and an odd tail: three 32 MiB ranges, the last a short one.
  std::string bytes((size_t(70) << 20) + 12345, '\0');
  std::mt19937 rng(7);
  for (size_t i = 0; i < bytes.size(); i += 4) {
    const uint32_t r = rng();
    for (size_t k = 0; k < 4 && i + k < bytes.size(); ++k) bytes[i + k] = char(r >> (8 * k));
  }
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  const Bytes got = read_file(path, 1 << 20);
  REQUIRE(got.size == bytes.size());
  CHECK(got.view() == bytes);
}
