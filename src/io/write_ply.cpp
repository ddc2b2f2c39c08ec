// meshsal: the PLY writer (binary little-endian, SPEC section 4).
// It goes through write_file_atomically (atomic_write.h): a failure never leaves a
// half-written or clobbered file.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <future>
#include <string>
#include <vector>

#include "io/colormap.h"
#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "io/atomic_write.h"
#include "io/mesh_io_internal.h"
#include "io/ply_types.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// PLY keeps colours as bytes: these channels are written as uchar (rounded, clamped).
bool is_colour_channel(const std::string& name) {
  return name == "red" || name == "green" || name == "blue" || name == "alpha";
}

// Records formatted at a time: a thread is started per chunk.
constexpr size_t kRecordsPerChunk = size_t(1) << 18;

// Writes `count` records, formatted `per_chunk` at a time by format(begin, end, buf) (which
// puts records [begin, end) in buf): the next chunk is formatted on a second thread
// while this one goes to the file, so the formatting and the system's copy into the page
// cache (as slow as the formatting on a VM: 1.1 s of 387 MB) overlap.
void write_records(std::FILE* f, const std::string& path, size_t count, size_t per_chunk,
                   const std::function<void(size_t, size_t, std::vector<char>&)>& format) {
  if (count == 0) return;
  std::vector<char> ready, next;
  format(0, std::min(count, per_chunk), ready);
  for (size_t begin = per_chunk; ; begin += per_chunk) {
    std::future<void> formatting;
    if (begin < count) {
      next.clear();
      formatting = std::async(std::launch::async, [&, begin] { format(begin, std::min(count, begin + per_chunk), next); });
    }
    try {
      write_all(f, ready.data(), ready.size(), path);
    } catch (...) {
      if (formatting.valid()) formatting.wait();
      throw;
    }
    if (!formatting.valid()) break;
    formatting.get();
    std::swap(ready, next);
  }
}

}  // namespace

void write_ply(const std::string& path, const Mesh& mesh,
               const std::vector<PlyFloatProperty>& properties, const std::vector<uint8_t>& rgb_bytes) {
  check_mesh(path, mesh);
  const std::vector<uint8_t>* rgb = rgb_bytes.empty() ? nullptr : &rgb_bytes;
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
  // The mesh's own attributes, unless a given property or the colours replace them.
  std::vector<const VertexAttribute*> attrs;
  for (const VertexAttribute& a : mesh.attributes) {
    bool replaced = rgb && (a.name == "red" || a.name == "green" || a.name == "blue");
    for (const PlyFloatProperty& p : properties) replaced |= p.name == a.name;
    if (replaced) continue;
    if (a.name.empty() || a.name.find_first_of(" \t\r\n") != std::string::npos)
      throw Error(path + ": cannot write: bad attribute name '" + a.name + "'");
    if (a.values.size() != nv)
      throw Error(path + ": cannot write: attribute '" + a.name + "' has " + std::to_string(a.values.size()) +
                  " values for " + std::to_string(nv) + " vertices");
    attrs.push_back(&a);
  }
  if (rgb && rgb->size() != 3 * nv)
    throw Error(path + ": cannot write: " + std::to_string(rgb->size()) + " colour bytes for " +
                std::to_string(nv) + " vertices (need 3 each)");

  // Positions in the model's own coordinates (model_position), in double where float would
  // move them (positions_need_double).
  const bool wide = positions_need_double(mesh);
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by meshsal\n";
  header += "element vertex " + std::to_string(nv) + "\n";
  header += wide ? "property double x\nproperty double y\nproperty double z\n"
                 : "property float x\nproperty float y\nproperty float z\n";
  for (const VertexAttribute* a : attrs)
    header += (is_colour_channel(a->name) ? "property uchar " : "property float ") + a->name + "\n";
  for (const PlyFloatProperty& p : properties) header += "property float " + p.name + "\n";
  if (rgb) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header += "element face " + std::to_string(mesh.triangle_count()) + "\n";
  header += "property list uchar int vertex_indices\nend_header\n";

  write_file_atomically(path, [&](std::FILE* f) {
    write_all(f, header.data(), header.size(), path);
    size_t vertex_bytes = (wide ? 24 : 12) + 4 * properties.size() + (rgb ? 3 : 0);
    for (const VertexAttribute* a : attrs) vertex_bytes += is_colour_channel(a->name) ? 1 : 4;
    // Records go straight into a buffer sized for the chunk (appending field by field was
    // as slow as the file's writing).
    std::vector<uint8_t> colour_attr(attrs.size());
    for (size_t i = 0; i < attrs.size(); ++i) colour_attr[i] = is_colour_channel(attrs[i]->name);
    write_records(f, path, nv, kRecordsPerChunk, [&](size_t begin, size_t end, std::vector<char>& buf) {
      buf.resize((end - begin) * vertex_bytes);
      char* out = buf.data();
      for (size_t v = begin; v < end; ++v) {
        double xyz[3];
        model_position(mesh, v, xyz);
        for (int k = 0; k < 3; ++k) {
          if (wide) put_le(out, xyz[k]);
          else put_le(out, static_cast<float>(xyz[k]));
        }
        for (size_t i = 0; i < attrs.size(); ++i) {
          const float x = attrs[i]->values[v];
          if (colour_attr[i])
            *out++ = char(uint8_t(x >= 255 ? 255 : x > 0 ? std::lround(x) : 0));  // NaN -> 0
          else
            put_le(out, x);
        }
        for (const PlyFloatProperty& p : properties) put_le(out, static_cast<float>((*p.values)[v]));
        if (rgb) std::memcpy(out, rgb->data() + 3 * v, 3), out += 3;
      }
    });
    write_records(f, path, mesh.triangle_count(), kRecordsPerChunk, [&](size_t begin, size_t end, std::vector<char>& buf) {
      buf.resize((end - begin) * kPlyTriangleBytes);
      char* out = buf.data();
      for (size_t t = begin; t < end; ++t) put_ply_triangle(out, &mesh.triangles[3 * t]);
    });
  });
}

void write_saliency_ply(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency,
                        const std::vector<PlyFloatProperty>& extra, const std::vector<uint8_t>& point_flags) {
  const std::vector<uint8_t>* is_point = point_flags.empty() ? nullptr : &point_flags;
  check_mesh(path, mesh);
  if (saliency.size() != mesh.vertex_count())
    throw Error(path + ": cannot write: " + std::to_string(saliency.size()) + " saliency values for " +
                std::to_string(mesh.vertex_count()) + " vertices");
  std::vector<PlyFloatProperty> props{{"quality", &saliency}};
  props.insert(props.end(), extra.begin(), extra.end());
  // The pictures' colour scale (ColorRange's default: minimum..maximum, square-root position).
  if (is_point && is_point->size() != mesh.vertex_count())
    throw Error(path + ": cannot write: " + std::to_string(is_point->size()) + " mesh-point flags for " +
                std::to_string(mesh.vertex_count()) + " vertices");
  const std::vector<uint8_t> rgb =
      colormap_values(saliency, is_point ? *is_point : referenced_vertices(mesh));
  write_ply(path, mesh, props, rgb);
}

}  // namespace meshsal
