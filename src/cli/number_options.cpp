#include "number_options.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "meshsal/meshsal.h"
#include "core/number_text.h"
#include "saliency/saliency.h"

namespace meshsal::cli {
namespace {

using meshsal::number_text;

// CLI11 puts "--OPTION: " in front of a validator's message: a library message that starts
// with what it parses ("color range: ...", "scales must ...": the library names no flags)
// loses that, so the name is said once.
std::string without_option_name(std::string message, const std::string& subject) {
  if (message.compare(0, subject.size(), subject) == 0) {
    size_t cut = subject.size();
    if (message.compare(cut, 2, ": ") == 0) cut += 2;
    else if (message.compare(cut, 1, " ") == 0) cut += 1;
    else return message;
    message.erase(0, cut);
  }
  return message;
}

}  // namespace

CLI::Validator finite_in(double lo, double hi, bool lo_open) {
  const std::string range = (lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + "]";
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double x = std::strtod(text.c_str(), &end);
        const bool parsed = !text.empty() && end && *end == '\0' && errno != ERANGE;
        if (!parsed || !std::isfinite(x) || x > hi || (lo_open ? !(x > lo) : !(x >= lo)))
          return "must be a finite number in " + range + ", got '" + text + "'";
        return "";
      },
      "in " + range);
}

CLI::Validator color_range_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          meshsal::parse_color_range(text);
        } catch (const meshsal::Error& e) {
          return without_option_name(e.what(), "color range");
        }
        return "";
      },
      "LO,HI");
}

CLI::Option* add_elevation_option(CLI::App& app, std::string* text) {
  char band[64];
  std::snprintf(band, sizeof band, "%g,%g", meshsal::kDefaultElevationMin, meshsal::kDefaultElevationMax);
  return app
      .add_option("--elevation", *text,
                  std::string("MIN,MAX latitudes in degrees (in the frame of --up) the best view may look from "
                              "(default ") +
                      band + ": a little above the horizon; -90,90: the whole sphere, the paper's search)")
      ->check(CLI::Validator(
          [](std::string& t) -> std::string {
            try {
              meshsal::parse_elevation_range(t);
            } catch (const meshsal::Error& e) {
              return e.what();
            }
            return "";
          },
          "MIN,MAX"));
}

CLI::Validator whole_in(long long lo, long long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const long long x = std::strtoll(text.c_str(), &end, 10);
        if (text.empty() || !end || *end != '\0' || errno == ERANGE || x < lo || x > hi)
          return "must be a whole number in " + range + ", got '" + text + "'";
        return "";
      },
      "in " + range);
}

CLI::Validator lod_list() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          meshsal::parse_lod_levels(text);
        } catch (const meshsal::Error& e) {
          return without_option_name(e.what(), "lod");
        }
        return "";
      },
      "LIST");
}

CLI::Validator memory_size() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          meshsal::parse_memory_size(text);
        } catch (const meshsal::Error& e) {
          return without_option_name(e.what(), "memory size");
        }
        return "";
      },
      "SIZE");
}

CLI::Validator scales_list() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          meshsal::parse_scales(text);
        } catch (const meshsal::Error& e) {
          return without_option_name(e.what(), "scales");
        }
        return "";
      },
      "list");
}

CLI::Option* add_temp_dir_option(CLI::App& app, std::string* dir) {
  return app.add_option("--temp-dir", *dir,
                        "Where --memory-limit keeps its tiles (default $TMPDIR or /tmp): a folder meshsal-tiles-XXXXXX,\n"
                        "locked while the run lives and removed at its end (an error or a signal such as Ctrl-C,\n"
                        "SIGTERM or SIGHUP included). One that a crashed or kill -9'd run left is stale: its lock\n"
                        "is free, and the next run with that --temp-dir removes it (not on NFS and other network\n"
                        "file systems, whose locks cannot be trusted: there it says so and leaves it)");
}

CLI::Option* add_threads_option(CLI::App& app, unsigned& threads, const std::string& help) {
  return app.add_option("--threads", threads, help)
      ->capture_default_str()
      ->check(whole_in(0, kMaxThreadsOption));
}

}  // namespace meshsal::cli
