// What each libFuzzer target does with one input, shared by the targets (fuzz_*.cpp) and
// by the Catch2 test that replays the corpus and the regression files in the normal suite.
// A meshsal::Error is the expected refusal; anything else (another exception, a crash, a
// sanitizer report) is a finding. Limits keep each input fast.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "meshsal/meshsal.h"
#include "saliency/saliency.h"

namespace meshsal_fuzz {

// Loads `data` as a file called `name`: "" (and the mesh) when it loads, else the Error.
// `attributes`: LoadOptions::attributes (OBJ vt/vn corners, PLY properties and seams).
inline std::string load(const uint8_t* data, size_t size, const std::string& name, meshsal::Mesh& mesh,
                        bool attributes = false) {
  meshsal::LoadOptions options;
  options.max_input_bytes = 8u << 20;
  options.attributes = attributes;
  try {
    meshsal::VertexProperties properties;
    mesh = meshsal::load_mesh_bytes(std::string_view(reinterpret_cast<const char*>(data), size), name,
                                    &properties, options);
    return "";
  } catch (const meshsal::Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: not a meshsal::Error: %s\n", name.c_str(), e.what());
    std::abort();
  }
}

// The targets: obj, off, ply, stl (the bytes are the file), gz (the first byte picks the format
// inside, the rest is the .gz file) and saliency (the first byte picks the format; small
// meshes that load go through the CPU saliency pipeline). Returns load's result.
inline std::string run_target(const std::string& target, const uint8_t* data, size_t size) {
  meshsal::Mesh mesh;
  if (target == "obj" || target == "off" || target == "ply" || target == "stl") {
    if (target == "obj" || target == "ply") {  // the attribute paths too (what simplify reads)
      meshsal::Mesh with_attributes;
      load(data, size, "fuzz." + target, with_attributes, true);
    }
    return load(data, size, "fuzz." + target, mesh);
  }
  if (size < 1) return "empty input";
  static const char* const formats[] = {"obj", "off", "ply"};
  const std::string name = std::string("fuzz.") + formats[data[0] % 3] + (target == "gz" ? ".gz" : "");
  const std::string outcome = load(data + 1, size - 1, name, mesh);
  if (!outcome.empty() || target != "saliency" || mesh.vertex_count() > 64 || mesh.triangle_count() > 128)
    return outcome;
  meshsal::SaliencyOptions options;
  options.threads = 1;
  options.smoothed = true;
  try {
    meshsal::compute_saliency_cpu(mesh, options);
  } catch (const meshsal::Error& e) {
    return std::string("saliency: ") + e.what();
  }
  return "";
}

}  // namespace meshsal_fuzz
