// meshsal CLI: range checks for numeric options. A value outside its range (or NaN, Inf,
// junk) is a usage error: exit 2, "error: --OPTION: must be ... in [LO, HI], got X".
#pragma once
#include <string>

#include <CLI/CLI.hpp>

namespace meshsal::cli {

// Most threads any command starts (--threads): more gains nothing and can exhaust the
// process limit. The library caps the same way (meshsal::kMaxThreads).
constexpr unsigned kMaxThreadsOption = 1024;

// The value must be a finite number in [lo, hi] ((lo, hi] when lo_open).
CLI::Validator finite_in(double lo, double hi, bool lo_open = false);

// The value must be a whole number in [lo, hi].
CLI::Validator whole_in(long long lo, long long hi);

// --scales: a comma-separated list of numbers in (0, 100] (meshsal::parse_scales).
CLI::Validator scales_list();

// --lod: ratios or face counts as meshsal::parse_lod_levels reads them (their order too),
// so a bad list is a usage error before the input is read.
CLI::Validator lod_list();

// Every size option (--memory-limit): a size as meshsal::parse_memory_size reads it.
CLI::Validator memory_size();

// What a size option's help says of the syntax (parse_memory_size's).
constexpr const char* kSizeSyntax = "SIZE: bytes, or a number with K, M, G or T (powers of 1024), e.g. 700M, 1.5G";

// Adds `--temp-dir DIR` bound to `dir`: where --memory-limit keeps its tiles, and what
// becomes of a folder a killed run left (the same words for every command).
CLI::Option* add_temp_dir_option(CLI::App& app, std::string* dir);

// --color-range: LO,HI as meshsal::parse_color_range reads it.
CLI::Validator color_range_check();

// Adds `--elevation MIN,MAX` (degrees, meshsal::parse_elevation_range checks it) bound to
// `text`, for every command that picks a view.
CLI::Option* add_elevation_option(CLI::App& app, std::string* text);

// Adds `--threads N` bound to `threads`, 0..kMaxThreadsOption (0 = all cores).
CLI::Option* add_threads_option(CLI::App& app, unsigned& threads, const std::string& help);

}  // namespace meshsal::cli
