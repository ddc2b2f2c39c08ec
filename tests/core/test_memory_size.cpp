// Issue 36 (9): one reading of a size, meshsal::parse_memory_size, for every --memory-limit
// (saliency, simplify, batch) and Python's memory_limit="700M": a decimal number with an
// optional K/M/G/T (powers of 1024), truncated to whole bytes, exactly; anything else a
// usage error (exit 2) before the input is read; a bare number under 1M suggests the unit.
#include <filesystem>
#include <string>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "test_util.h"

using namespace meshsal;
using namespace meshsal_test;

TEST_CASE("memory size: parse_memory_size reads a decimal size exactly, truncated to whole bytes", "[outofcore]") {
  CHECK(parse_memory_size("700M") == uint64_t(700) << 20);
  CHECK(parse_memory_size("700m") == uint64_t(700) << 20);
  CHECK(parse_memory_size("700MB") == uint64_t(700) << 20);
  CHECK(parse_memory_size("1.5G") == uint64_t(3) << 29);
  CHECK(parse_memory_size("2T") == uint64_t(2) << 40);
  CHECK(parse_memory_size("0.3K") == 307);  // 307.2 truncated
  CHECK(parse_memory_size(".5M") == uint64_t(1) << 19);
  CHECK(parse_memory_size("3.M") == uint64_t(3) << 20);
  // Exact, not through a double (which rounds this to 2048).
  CHECK(parse_memory_size("1.99999999999999999999999K") == 2047);
  CHECK(parse_memory_size("1048576") == uint64_t(1) << 20);  // a bare number: bytes, from 1M up
  CHECK(parse_memory_size("0001048576") == uint64_t(1) << 20);
  CHECK(parse_memory_size("16777215T") == ((uint64_t(1) << 24) - 1) << 40);
  CHECK(parse_memory_size("18446744073709551615") == UINT64_MAX);
}

TEST_CASE("memory size: zero, overflow, non-finite, hex, signs and junk are errors that say why", "[outofcore]") {
  const auto message = [](const std::string& text) {
    try {
      parse_memory_size(text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  for (const char* bad : {"", "M", ".", "abc", "inf", "INF", "nan", "-1", "-5M", "+5M", "0x10M", "0x100000", "1e3M",
                          "1e30G", " 5M", "5M ", "5 M", "5..M", "1.2.3M", "5MM", "5Q", "5KiB", "12Q"}) {
    INFO("'" << bad << "': " << message(bad));
    CHECK(message(bad).find("memory size must be a decimal number of bytes with an optional K, M, G or T") == 0);
  }
  CHECK(message("0") == "memory size must be more than 0, got '0'");
  CHECK(message("0.000M") == "memory size must be more than 0, got '0.000M'");
  CHECK(message("0.0001K") == "memory size '0.0001K' is less than one byte");
  CHECK(message("16777216T") == "memory size '16777216T' is more bytes than a 64-bit count holds");
  CHECK(message("18446744073709551616") == "memory size '18446744073709551616' is more bytes than a 64-bit count holds");
  // A bare number under 1M: surely a forgotten unit.
  CHECK(message("100") == "memory size '100' is 100 bytes: give a unit, e.g. 100M (K, M, G or T)");
  CHECK(message("0.5") == "memory size '0.5' is 0 bytes: give a unit, e.g. 0.5G (K, M, G or T)");
  CHECK(message("1048575") == "memory size '1048575' is 1048575 bytes: give a unit, e.g. 1048575M (K, M, G or T)");
}

TEST_CASE("cli: every --memory-limit refuses a bad size as a usage error, before the input is read",
          "[outofcore][cli]") {
  const auto dir = scratch_dir("memory_size_cli");
  // The input does not exist: a size error must come first (exit 2, not the loader's 1).
  const std::string in = quoted((dir / "missing.ply").string());
  for (const std::string size : {"0.5", "abc", "inf", "-1", "0x10M", "100", "1e30G", "16777216T"}) {
    for (const std::string command : {"saliency " + in + " -o " + quoted((dir / "o.ply").string()),
                                      "simplify " + in + " -o " + quoted((dir / "o.ply").string()) + " --ratio 0.5",
                                      "batch " + in + " -o " + quoted((dir / "out").string())}) {
      INFO(command << " --memory-limit=" << size);
      check_usage_error(command + " --memory-limit=" + size, "--memory-limit: ", dir);
    }
  }
  const CliRun bare = run_cli("saliency " + in + " -o " + quoted((dir / "o.ply").string()) + " --memory-limit 100", dir);
  CHECK(bare.err == "error: --memory-limit: '100' is 100 bytes: give a unit, e.g. 100M (K, M, G or T) (see --help)\n");
  const CliRun junk = run_cli("simplify " + in + " -o " + quoted((dir / "o.ply").string()) + " --ratio 0.5 --memory-limit 0x10M", dir);
  CHECK(junk.err == "error: --memory-limit: must be a decimal number of bytes with an optional K, M, G or T (powers of "
                    "1024, e.g. 700M, 1.5G), got '0x10M' (see --help)\n");
}

TEST_CASE("cli: a limit too small is said as given (1K, not 1M)", "[outofcore][cli]") {
  const auto dir = scratch_dir("memory_size_small");
  const std::string in = (dir / "sphere.ply").string();
  write_ply(in, make_bumpy_sphere(3), {});
  for (const std::string command : {"saliency", "simplify"}) {
    const CliRun r = run_cli(command + " " + quoted(in) + " -o " + quoted((dir / "o.ply").string()) +
                                 (command == "simplify" ? " --ratio 0.5" : "") + " --backend cpu --memory-limit 1K",
                             dir);
    INFO(command << ": " << r.err);
    CHECK(r.rc == 1);
    CHECK(r.err.find("error: memory limit 1K is too small") == 0);
    CHECK(!std::filesystem::exists(dir / "o.ply"));
  }
}

TEST_CASE("cli: --help says the size syntax and what a stale temporary folder is", "[cli][outofcore]") {
  for (const char* command : {"saliency", "simplify", "batch"}) {
    const CliRun r = run_cli(std::string(command) + " --help");
    INFO(command << " --help:\n" << r.out);
    CHECK(r.rc == 0);
    CHECK(r.out.find("K, M, G or T (powers of 1024)") != std::string::npos);
    CHECK(r.out.find("meshsal-tiles-XXXXXX") != std::string::npos);
    CHECK(r.out.find("is stale") != std::string::npos);
  }
}
