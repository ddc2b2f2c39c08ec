// What each libFuzzer target does with one input, shared by the targets (fuzz_*.cpp) and
// by the Catch2 test that replays the corpus and the regression files in the normal suite.
// A meshsal::Error is the expected refusal; anything else (another exception, a crash, a
// sanitizer report) is a finding. Limits keep each input fast.
#pragma once
#include <algorithm>
#include <cmath>
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
#include "core/mesh_points.h"
#include "io/mesh_io_internal.h"
#include "io/ply_stream.h"
#include "io/read_bytes.h"
#include "io/read_observer.h"
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

// A PLY read with an observer (io/read_observer.h), as a GPU run reads it: the arrays it is
// told of read at once (under ASan, a told array that is gone is a report), the calls in
// order (positions, triangles, then the end), and the mesh the same as `plain`, the load
// without one ("" when it failed the same way).
inline void check_observed_ply(const uint8_t* data, size_t size, const meshsal::Mesh& plain, const std::string& outcome) {
  struct Observer final : meshsal::ReadObserver {
    std::string calls;
    std::vector<float> positions;
    std::vector<uint32_t> triangles;
    bool open = true;
    void positions_read(const float* p, size_t n) override {
      calls += open ? "p" : "P";
      positions.assign(p, p + 3 * n);
    }
    void triangles_read(const uint32_t* t, size_t n) override {
      calls += open ? "t" : "T";
      triangles.assign(t, t + 3 * n);
    }
    void read_ended(bool returned) noexcept override {
      calls += returned ? "r" : "e";
      open &= returned;
    }
  } seen;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  if (meshsal::has_gzip_magic(bytes)) return;  // the plain load inflates it first
  std::string got;
  meshsal::Mesh mesh;
  try {
    const meshsal::EndObserver end(&seen);  // as load_mesh ends it
    mesh = meshsal::load_ply_bytes(bytes, "fuzz.ply", nullptr, false, nullptr, nullptr, &seen);
    meshsal::validate_mesh(mesh);
  } catch (const meshsal::Error& e) {
    got = e.what();
  } catch (const std::exception& e) {  // what load_mesh turns into "out of memory" Errors
    got = std::string("out of memory: ") + e.what();
  }
  // The calls: p, t (either may be missing), any e's (a throw; positions made again),
  // then r where the load returned.
  const std::string& c = seen.calls;
  size_t i = 0;
  if (i < c.size() && c[i] == 'p') ++i;
  if (i < c.size() && c[i] == 't') ++i;
  while (i < c.size() && c[i] == 'e') ++i;
  const bool returned = i < c.size() && c[i] == 'r';
  const bool ordered = i + (returned ? 1 : 0) == c.size() && returned == got.empty() && !c.empty();
  // Unless ended, what it was told is what the mesh holds.
  const bool told_right =
      !got.empty() || c.find('e') != std::string::npos ||
      ((c.find('p') == std::string::npos ||
        (seen.positions.size() == mesh.positions.size() &&
         std::memcmp(seen.positions.data(), mesh.positions.data(), 4 * mesh.positions.size()) == 0)) &&
       (c.find('t') == std::string::npos || seen.triangles == mesh.triangles));
  const bool same = got.empty() == outcome.empty() &&
                    (!got.empty() || (mesh.positions.size() == plain.positions.size() &&
                                      std::memcmp(mesh.positions.data(), plain.positions.data(), 4 * mesh.positions.size()) == 0 &&
                                      mesh.triangles == plain.triangles &&
                                      std::memcmp(mesh.origin, plain.origin, sizeof mesh.origin) == 0));
  if (!ordered || !same || !told_right) {
    std::fprintf(stderr, "ply: the observed read differs (calls '%s', error '%s' against '%s')\n", seen.calls.c_str(),
                 got.c_str(), outcome.c_str());
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
      std::vector<double> xyz(3 * 1024), all_xyz;
      for (size_t got; (got = s.read_vertices(xyz.data(), 1024)) > 0;) all_xyz.insert(all_xyz.end(), xyz.begin(), xyz.begin() + long(3 * got));
      std::vector<uint32_t> triangles, all_triangles;
      while (s.read_faces(triangles, 1024) > 0) all_triangles.insert(all_triangles.end(), triangles.begin(), triangles.end()), triangles.clear();
      // A file read in ranges (the ranks building a store): two halves, read apart, are the
      // whole read's.
      if (s.ranged()) try {
        const uint64_t nv = s.vertex_count(), nf = s.face_count();
        std::vector<double> part_xyz;
        std::vector<uint32_t> part_triangles;
        for (int half = 1; half >= 0; --half) {
          meshsal::PlyStream p(path);
          const uint64_t v0 = nv * uint64_t(half) / 2, v1 = nv * uint64_t(half + 1) / 2;
          p.seek_vertex(v0);
          std::vector<double> got_xyz(3 * (v1 - v0));
          for (uint64_t v = v0; v < v1;) {
            const size_t got = p.read_vertices(&got_xyz[3 * (v - v0)], size_t(v1 - v));
            if (got == 0) std::abort();
            v += got;
          }
          const uint64_t f0 = nf * uint64_t(half) / 2, f1 = nf * uint64_t(half + 1) / 2;
          p.seek_face(f0);
          std::vector<uint32_t> got_triangles;
          for (uint64_t f = f0; f < f1;) {
            const size_t got = p.read_faces(got_triangles, size_t(f1 - f));
            if (got == 0) std::abort();
            f += got;
          }
          part_xyz.insert(part_xyz.begin(), got_xyz.begin(), got_xyz.end());
          part_triangles.insert(part_triangles.begin(), got_triangles.begin(), got_triangles.end());
        }
        // (Bits compared: a file's NaN is a value as read like any other here.)
        const bool same_xyz = part_xyz.size() == all_xyz.size() &&
                              (all_xyz.empty() || std::memcmp(part_xyz.data(), all_xyz.data(), 8 * all_xyz.size()) == 0);
        if (!same_xyz || part_triangles != all_triangles) {
          std::fprintf(stderr, "plystream: ranges read apart differ from the whole read\n");
          std::abort();
        }
      } catch (const meshsal::Error& e) {  // the whole file read: its halves must too
        std::fprintf(stderr, "plystream: a range of a file read whole failed: %s\n", e.what());
        std::abort();
      }
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

// The meshes the rows target joins its rows to: a tetrahedron with corners at the origin
// and at 1 on each axis (the positions the seeds in corpus/rows use) and vertex 4, a twin
// of vertex 0 that no triangle uses (one row reaches both, as at a seam); with `stray`,
// also vertex 5 at x = 1e15, used by no triangle either (a stray point far from the model,
// which a prediction's file may hold).
inline const meshsal::Mesh& rows_mesh(bool stray) {
  auto make = [](bool with_stray) {
    const double xyz[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1e15, 0, 0};
    const uint32_t tris[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    return meshsal::make_mesh(xyz, with_stray ? 6 : 5, tris, 12);
  };
  static const meshsal::Mesh meshes[2] = {make(false), make(true)};
  return meshes[stray];
}

// join_vertex_rows(mesh, rows), checked against the rule it implements, computed here by
// brute force: a row reaches every vertex whose model position (minus the origin, as the
// join computes) is within 1e-6 of the diagonal of the mesh points; two rows that give one
// vertex different values are an Error. A result or an Error that differs from the rule's
// is a finding. Returns "" or the Error.
inline std::string join_checked(const meshsal::Mesh& mesh, const meshsal::VertexRows& rows) {
  auto finding = [](const std::string& what) {
    std::fprintf(stderr, "join_vertex_rows: %s\n", what.c_str());
    std::abort();
  };
  const size_t n = mesh.vertex_count(), count = rows.values.size();
  const std::vector<double> model = meshsal::model_positions(mesh);
  const double tol = 1e-6 * meshsal::mesh_points_bbox(mesh, meshsal::referenced_vertices(mesh)).diagonal();
  std::vector<double> values(n, 0.0);
  std::vector<uint8_t> has(n, 0);
  size_t matched = 0, conflict_line = 0;
  std::vector<size_t> unmatched_lines;
  for (size_t r = 0; r < count && !conflict_line; ++r) {
    bool reached = false;
    for (size_t v = 0; v < n; ++v) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double d = (model[3 * v + k] - mesh.origin[k]) - (rows.xyz[3 * r + k] - mesh.origin[k]);
        d2 += d * d;
      }
      if (!(d2 <= tol * tol)) continue;
      reached = true;
      if (has[v] && values[v] != rows.values[r]) conflict_line = rows.lines[r];
      values[v] = rows.values[r];
      has[v] = 1;
    }
    matched += reached;
    if (!reached && unmatched_lines.size() < 20) unmatched_lines.push_back(rows.lines[r]);
  }
  meshsal::JoinedRows j;
  try {
    j = meshsal::join_vertex_rows(mesh, rows);
  } catch (const meshsal::Error& e) {
    const std::string what = e.what();
    if (!conflict_line) finding("refused rows that give no vertex two values: " + what);
    if (what.find(" and " + std::to_string(conflict_line) + " give vertex ") == std::string::npos)
      finding("the refusal names another line than " + std::to_string(conflict_line) + ": " + what);
    return what;
  } catch (const std::exception& e) {
    finding(std::string("not a meshsal::Error: ") + e.what());
  }
  if (conflict_line) finding("took rows that give a vertex two values (line " + std::to_string(conflict_line) + ")");
  size_t without = 0;
  for (uint8_t h : has) without += h == 0;
  if (j.rows != count || j.matched_rows != matched || j.unmatched_rows != count - matched ||
      j.unmatched_lines != unmatched_lines || j.vertices_without_value != without)
    finding("its row counts differ from the rule's");
  if (j.has_value != has || j.values != values) finding("its values differ from the rule's");
  return "";
}

// Ground truth as text rows (meshsal eval's GT; gzip is the caller's): parse_vertex_rows
// over the bytes as the file fuzz.txt with the value in `column`, and the rows it returns
// joined to both rows_mesh()es by join_checked. "" when all succeed, else the first Error;
// join's messages name no file, so "fuzz.txt: join: " goes in front of them. Rows that do
// not add up (counts, lines, a non-finite number let through) are a finding, as a crash is.
inline std::string read_rows(const uint8_t* data, size_t size, int column) {
  const std::string name = "fuzz.txt";
  meshsal::VertexRows rows;
  try {
    rows = meshsal::parse_vertex_rows(std::string(reinterpret_cast<const char*>(data), size), name, column);
  } catch (const meshsal::Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: not a meshsal::Error: %s\n", name.c_str(), e.what());
    std::abort();
  }
  auto finding = [&](const char* what) {
    std::fprintf(stderr, "%s: parse_vertex_rows: %s\n", name.c_str(), what);
    std::abort();
  };
  const size_t n = rows.values.size();
  if (n == 0 || rows.xyz.size() != 3 * n || rows.lines.size() != n || rows.columns < 4 ||
      (column != 0 && size_t(column) > rows.columns))
    finding("rows that do not add up");
  for (size_t r = 0; r < n; ++r) {
    if (rows.lines[r] < 1 || (r > 0 && rows.lines[r] <= rows.lines[r - 1])) finding("row lines not increasing from 1");
    if (!std::isfinite(rows.values[r])) finding("a non-finite value let through");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(rows.xyz[3 * r + k])) finding("a non-finite coordinate let through");
  }
  std::string outcome;
  for (bool stray : {false, true}) {
    const std::string joined = join_checked(rows_mesh(stray), rows);
    if (outcome.empty() && !joined.empty()) outcome = name + ": join: " + joined;
  }
  return outcome;
}

// The targets: plystream (read_stream), obj, off, ply, stl, gltf, glb (the bytes are the file), gz (the first byte picks the format
// inside, the rest is the .gz file), saliency (the first byte picks the format; small
// meshes that load go through the CPU saliency pipeline) and rows (read_rows: the first
// byte picks the value's column, its value mod 8: 0 the last, 1-3 refused, else that
// column; a digit '0'-'7' picks its own number; the rest is the text). Returns load's
// result.
inline std::string run_target(const std::string& target, const uint8_t* data, size_t size) {
  meshsal::Mesh mesh;
  if (target == "plystream") return read_stream(data, size);
  if (target == "rows") {
    if (size < 1) return "empty input";
    return read_rows(data + 1, size - 1, data[0] % 8);
  }
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
    const std::string outcome = load(data, size, "fuzz." + target, mesh);
    if (target == "ply") check_observed_ply(data, size, mesh, outcome);
    return outcome;
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
