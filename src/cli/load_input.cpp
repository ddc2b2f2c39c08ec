// meshsal CLI: load_input (see load_input.h).
#include "load_input.h"
#include "json_string.h"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "io/text_scan.h"

namespace meshsal::cli {

std::string mesh_extension(const std::string& path) {
  std::string name = path.substr(path.find_last_of('/') + 1);  // npos + 1 == 0
  for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (name.size() > 3 && name.compare(name.size() - 3, 3, ".gz") == 0) name.resize(name.size() - 3);
  const size_t dot = name.find_last_of('.');
  return dot == std::string::npos ? std::string() : name.substr(dot);
}

meshsal::LoadOptions load_options() {
  meshsal::LoadOptions options;
  const char* env = std::getenv("MESHSAL_MAX_INPUT");
  if (!env || !*env) return options;
  std::string_view s(env);
  uint64_t scale = 1;
  const char unit = static_cast<char>(std::toupper(static_cast<unsigned char>(s.back())));
  if (unit == 'K' || unit == 'M' || unit == 'G') {
    scale = uint64_t(1) << (unit == 'K' ? 10 : unit == 'M' ? 20 : 30);
    s.remove_suffix(1);
  }
  uint64_t n = 0;
  if (!meshsal::parse_number(s, n) || n == 0 || n > UINT64_MAX / scale)
    throw meshsal::Error("MESHSAL_MAX_INPUT: '" + std::string(env) +
                         "' is not a byte count (a positive whole number, optionally followed by K, M or G)");
  options.max_input_bytes = n * scale;
  return options;
}

meshsal::LoadedMesh load_input_mesh(const std::string& path, bool attributes, bool regular_only) {
  meshsal::LoadOptions options = load_options();
  options.regular_files_only = regular_only;
  options.attributes = attributes;
  return meshsal::read_mesh(path, options);
}

meshsal::Mesh load_input(const std::string& path, bool quiet) {
  meshsal::LoadedMesh read = load_input_mesh(path, false);
  const meshsal::LoadReport& report = read.report;
  if (report.welded_corners && !quiet)
    std::fprintf(stderr, "note: %s: welded %llu STL corners into %zu shared vertices\n", printable(path).c_str(),
                 static_cast<unsigned long long>(report.welded_corners), read.mesh.vertex_count());
  return std::move(read.mesh);
}

}  // namespace meshsal::cli
