// What each libFuzzer target does with one input, shared by the targets (fuzz_*.cpp) and
// by the Catch2 test that replays the corpus and the regression files in the normal suite.
// A meshsal::Error is the expected refusal; anything else (another exception, a crash, a
// sanitizer report) is a finding. Limits keep each input fast.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>

#include <unistd.h>

#include <vector>

#include "io/gltf_assets.h"
#include "io/ply_stream.h"
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
    // read_mesh_bytes, not load_mesh_bytes: the PLY property reader is fuzzed too.
    mesh = meshsal::read_mesh_bytes(std::string_view(reinterpret_cast<const char*>(data), size), name, options).mesh;
    return "";
  } catch (const meshsal::Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: not a meshsal::Error: %s\n", name.c_str(), e.what());
    std::abort();
  }
}

// The out-of-core reader (io/ply_stream.h) over the bytes as a file: every vertex and face
// read through. "" when the file streams to its end, else the Error (a file that is not a
// binary PLY: "not a binary PLY").
inline std::string read_stream(const uint8_t* data, size_t size) {
  char path[] = "/tmp/meshsal_fuzz_plystream_XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) return "no temporary file";
  for (size_t at = 0; at < size;) {
    const ssize_t n = ::write(fd, data + at, size - at);
    if (n <= 0) break;
    at += size_t(n);
  }
  ::close(fd);
  std::string outcome;
  try {
    if (!meshsal::PlyStream::readable(path)) {
      outcome = "not a binary PLY";
    } else {
      meshsal::PlyStream s(path);
      std::vector<double> xyz(3 * 1024);
      while (s.read_vertices(xyz.data(), 1024) > 0) {
      }
      std::vector<uint32_t> triangles;
      while (s.read_faces(triangles, 1024) > 0) triangles.clear();
    }
  } catch (const meshsal::Error& e) {
    outcome = e.what();
    if (outcome.empty()) outcome = "empty message";
  } catch (const std::exception& e) {
    std::fprintf(stderr, "plystream: not a meshsal::Error: %s\n", e.what());
    std::abort();
  }
  ::unlink(path);
  // Messages name the input: the temporary file is "fuzz.plystream" there.
  for (size_t at; (at = outcome.find(path)) != std::string::npos;) outcome.replace(at, std::strlen(path), "fuzz.plystream");
  return outcome;
}

// A folder the glTF targets load their input from, so that the files a glTF names are
// really looked up: model/ holds what a model may read (mesh.bin: one triangle's positions
// and indices; sub/mesh.bin; tex.png) and links out of it (up -> .., out.bin ->
// ../secret.bin); beside model/ lie secret.bin (a valid buffer whose coordinates are all
// 4242) and secret.png (holding "SECRET-MARKER"). Made once per process, removed at exit.
struct ReferenceFixture {
  std::string root, model;
  ReferenceFixture() {
    root = "/tmp/meshsal_fuzz_refs_" + std::to_string(::getpid());
    model = root + "/model";
    std::string cmd = "rm -rf '" + root + "' && mkdir -p '" + model + "/sub'";
    if (std::system(cmd.c_str()) != 0) std::abort();
    const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, secret[9] = {4242, 4242, 4242, 4242, 4242, 4242, 4242, 4242, 4242};
    const uint32_t idx[3] = {0, 1, 2};
    put(model + "/mesh.bin", std::string(reinterpret_cast<const char*>(tri), 36) + std::string(reinterpret_cast<const char*>(idx), 12));
    put(model + "/sub/mesh.bin", std::string(reinterpret_cast<const char*>(tri), 36) + std::string(reinterpret_cast<const char*>(idx), 12));
    put(model + "/tex.png", std::string("\x89PNG\r\n\x1a\n", 8) + "meshsal-fuzz-texture");
    put(root + "/secret.bin", std::string(reinterpret_cast<const char*>(secret), 36) + std::string(reinterpret_cast<const char*>(idx), 12));
    put(root + "/secret.png", std::string("\x89PNG\r\n\x1a\n", 8) + "SECRET-MARKER");
    if (::symlink("..", (model + "/up").c_str()) != 0 || ::symlink("../secret.bin", (model + "/out.bin").c_str()) != 0) std::abort();
  }
  ~ReferenceFixture() {
    const std::string cmd = "rm -rf '" + root + "'";
    if (std::system(cmd.c_str()) != 0) std::fprintf(stderr, "could not remove %s\n", root.c_str());
  }
  static void put(const std::string& path, const std::string& bytes) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size()) std::abort();
    std::fclose(f);
  }
};

// Loads `data` as the file model/fuzz.EXT of the fixture, with attributes, and aborts when
// anything of the secret files reached the mesh. Returns "" or the Error, the folder taken
// off its start (so that it names "fuzz.EXT" as the other targets' messages do).
inline std::string load_in_folder(const uint8_t* data, size_t size, const std::string& ext) {
  static ReferenceFixture fixture;
  const std::string path = fixture.model + "/fuzz." + ext;
  ReferenceFixture::put(path, std::string(reinterpret_cast<const char*>(data), size));
  meshsal::LoadOptions options;
  options.max_input_bytes = 8u << 20;
  options.attributes = true;
  try {
    const meshsal::Mesh mesh = meshsal::load_mesh(path, options);
    for (double x : meshsal::model_positions(mesh))
      if (x == 4242) std::fprintf(stderr, "read secret.bin from outside the model's folder\n"), std::abort();
    if (mesh.gltf_assets)
      for (const auto& bytes : mesh.gltf_assets->image_bytes)
        if (std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()).find("SECRET-MARKER") != std::string_view::npos)
          std::fprintf(stderr, "read secret.png from outside the model's folder\n"), std::abort();
    return "";
  } catch (const meshsal::Error& e) {
    std::string what = e.what();
    const std::string folder = fixture.model + "/";
    if (what.rfind(folder, 0) == 0) what.erase(0, folder.size());
    return what;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: not a meshsal::Error: %s\n", path.c_str(), e.what());
    std::abort();
  }
}

// The targets: plystream (read_stream), obj, off, ply, stl, gltf, glb (the bytes are the file), gz (the first byte picks the format
// inside, the rest is the .gz file) and saliency (the first byte picks the format; small
// meshes that load go through the CPU saliency pipeline). Returns load's result.
inline std::string run_target(const std::string& target, const uint8_t* data, size_t size) {
  meshsal::Mesh mesh;
  if (target == "plystream") return read_stream(data, size);
  if (target == "gltf" || target == "glb") {
    // From memory (no file may be named), then as a file among others (the references).
    load(data, size, "fuzz." + target, mesh);
    return load_in_folder(data, size, target);
  }
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
