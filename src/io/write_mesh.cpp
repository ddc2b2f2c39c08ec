// meshsal: result writers (binary little-endian PLY per SPEC section 4, and OBJ).
// Both go through write_file_atomically (atomic_write.h): a failure never leaves a
// half-written or clobbered file.
#include <charconv>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "io/atomic_write.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// Appends the little-endian bytes of a 4-byte value.
template <typename T>
void append_le(std::vector<char>& buf, T value) {
  static_assert(sizeof(T) == 4, "4-byte values only");
  unsigned char b[4];
  std::memcpy(b, &value, 4);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  std::swap(b[0], b[3]);
  std::swap(b[1], b[2]);
#endif
  buf.insert(buf.end(), b, b + 4);
}

void check_mesh(const std::string& path, const Mesh& mesh) {
  if (mesh.positions.size() % 3 != 0 || mesh.triangles.size() % 3 != 0)
    throw Error(path + ": cannot write: mesh arrays are not multiples of 3");
  for (uint32_t i : mesh.triangles)
    if (i >= mesh.vertex_count())
      throw Error(path + ": cannot write: a triangle uses vertex " + std::to_string(i) +
                  " but the mesh has " + std::to_string(mesh.vertex_count()) + " vertices");
}

}  // namespace

void write_ply(const std::string& path, const Mesh& mesh,
               const std::vector<PlyFloatProperty>& properties, const std::vector<uint8_t>* rgb) {
  check_mesh(path, mesh);
  const size_t nv = mesh.vertex_count();
  if (nv > 0x7FFFFFFFu) throw Error(path + ": cannot write: too many vertices for PLY int indices");
  for (const PlyFloatProperty& p : properties) {
    if (p.name.empty() || p.name.find_first_of(" \t\r\n") != std::string::npos)
      throw Error(path + ": cannot write: bad property name '" + p.name + "'");
    if (!p.values || p.values->size() != nv)
      throw Error(path + ": cannot write: property '" + p.name + "' has " +
                  std::to_string(p.values ? p.values->size() : 0) + " values for " +
                  std::to_string(nv) + " vertices");
  }
  if (rgb && rgb->size() != 3 * nv)
    throw Error(path + ": cannot write: " + std::to_string(rgb->size()) + " colour bytes for " +
                std::to_string(nv) + " vertices (need 3 each)");

  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by meshsal\n";
  header += "element vertex " + std::to_string(nv) + "\n";
  header += "property float x\nproperty float y\nproperty float z\n";
  for (const PlyFloatProperty& p : properties) header += "property float " + p.name + "\n";
  if (rgb) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header += "element face " + std::to_string(mesh.triangle_count()) + "\n";
  header += "property list uchar int vertex_indices\nend_header\n";

  write_file_atomically(path, [&](std::FILE* f) {
    write_all(f, header.data(), header.size(), path);
    std::vector<char> buf;
    const size_t chunk = 1 << 16;
    buf.reserve(chunk * (12 + 4 * properties.size() + 3));
    for (size_t v = 0; v < nv; ++v) {
      for (int k = 0; k < 3; ++k) append_le(buf, mesh.positions[3 * v + k]);
      for (const PlyFloatProperty& p : properties) append_le(buf, static_cast<float>((*p.values)[v]));
      if (rgb) buf.insert(buf.end(), rgb->begin() + 3 * v, rgb->begin() + 3 * v + 3);
      if (buf.size() >= chunk * 12) {
        write_all(f, buf.data(), buf.size(), path);
        buf.clear();
      }
    }
    for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
      buf.push_back(3);
      for (int k = 0; k < 3; ++k) append_le(buf, static_cast<int32_t>(mesh.triangles[t + k]));
      if (buf.size() >= chunk * 12) {
        write_all(f, buf.data(), buf.size(), path);
        buf.clear();
      }
    }
    write_all(f, buf.data(), buf.size(), path);
  });
}

void write_obj(const std::string& path, const Mesh& mesh) {
  check_mesh(path, mesh);
  write_file_atomically(path, [&](std::FILE* f) {
    std::string out;
    out.reserve(1 << 20);
    char num[64];
    // One "key x y z" line; to_chars gives the shortest text that reads back to the same
    // float bits. Written out in blocks of about 1 MiB.
    auto add_line = [&](char key, auto x, auto y, auto z) {
      out += key;
      for (auto value : {x, y, z}) {
        auto r = std::to_chars(num, num + sizeof num, value);
        out += ' ';
        out.append(num, r.ptr);
      }
      out += '\n';
      if (out.size() > (1 << 20) - 256) {
        write_all(f, out.data(), out.size(), path);
        out.clear();
      }
    };
    out += "# written by meshsal\n";
    const float* p = mesh.positions.data();
    for (size_t v = 0; v < mesh.vertex_count(); ++v) add_line('v', p[3 * v], p[3 * v + 1], p[3 * v + 2]);
    const uint32_t* t = mesh.triangles.data();
    for (size_t i = 0; i < mesh.triangles.size(); i += 3)
      add_line('f', uint64_t(t[i]) + 1, uint64_t(t[i + 1]) + 1, uint64_t(t[i + 2]) + 1);
    write_all(f, out.data(), out.size(), path);
  });
}

}  // namespace meshsal
