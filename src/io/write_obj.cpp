// meshsal: the OBJ writer: v (with r g b where the mesh has colours or S is written),
// vt from texture-coordinate set 0, vn, mtllib and usemtl, f. Atomic as every writer.
#include <string>
#include <vector>

#include "core/model_frame.h"
#include "io/atomic_write.h"
#include "io/mesh_io_internal.h"
#include "io/text_writer.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// The attribute of `kind` set 0 component `component`, or null.
const VertexAttribute* role_attribute(const Mesh& mesh, AttributeKind kind, int component) {
  for (const VertexAttribute& a : mesh.attributes) {
    const AttributeRole r = attribute_role(a.name);
    if (r.kind == kind && r.set == 0 && r.component == component) return &a;
  }
  return nullptr;
}

void check_triangle_materials(const std::string& path, const Mesh& mesh) {
  const std::vector<uint32_t>& tm = mesh.triangle_material;
  if (tm.empty()) return;
  if (tm.size() != mesh.triangle_count())
    throw Error(path + ": cannot write: triangle_material has " + std::to_string(tm.size()) + " entries for " +
                std::to_string(mesh.triangle_count()) + " triangles");
  for (uint32_t m : tm)
    if (m >= mesh.materials.size())
      throw Error(path + ": cannot write: a triangle has material " + std::to_string(m) + " but the mesh has " +
                  std::to_string(mesh.materials.size()) + " materials");
}

}  // namespace

void write_obj_colours(const std::string& path, const Mesh& mesh, const std::vector<uint8_t>& rgb) {
  check_mesh(path, mesh);
  // vt from the first texture-coordinate set (u v, s t or texture_u texture_v), vn from
  // nx ny nz; other attributes have no place in OBJ (mesh_output_note names them).
  const VertexAttribute* uv[2] = {role_attribute(mesh, AttributeKind::TexCoord, 0), role_attribute(mesh, AttributeKind::TexCoord, 1)};
  if (!uv[0] || !uv[1]) uv[0] = uv[1] = nullptr;
  const VertexAttribute* nrm[3] = {find_attribute(mesh, "nx"), find_attribute(mesh, "ny"), find_attribute(mesh, "nz")};
  const bool has_vt = uv[0] != nullptr, has_vn = nrm[0] && nrm[1] && nrm[2];
  for (const VertexAttribute* a : {uv[0], uv[1], nrm[0], nrm[1], nrm[2]})
    if (a && a->values.size() != mesh.vertex_count())
      throw Error(path + ": cannot write: attribute '" + a->name + "' has " + std::to_string(a->values.size()) +
                  " values for " + std::to_string(mesh.vertex_count()) + " vertices");
  if (!rgb.empty() && rgb.size() != 3 * mesh.vertex_count())
    throw Error(path + ": cannot write: " + std::to_string(rgb.size()) + " colour bytes for " +
                std::to_string(mesh.vertex_count()) + " vertices (need 3 each)");
  check_triangle_materials(path, mesh);
  const std::vector<uint32_t>& tm = mesh.triangle_material;
  // Split twins (position_vertex) share one v line: a seam stays one surface in the file.
  const std::vector<uint64_t> v_line = welded_lines(path, mesh);
  const bool welded = !v_line.empty();
  write_file_atomically(path, [&](std::FILE* f) {
    TextWriter out(f, path, positions_need_double(mesh));
    // One "key x y z" line of floats.
    auto add_line = [&](const char* key, std::initializer_list<float> values) {
      out << key;
      for (float value : values) {
        out << ' ';
        out.number(value);
      }
      out.end_line();
    };
    out << "# written by meshsal\n";
    // The materials go into one library beside the output (write_material_files).
    if (!tm.empty()) out << "mtllib " << material_library_name(path) << "\n";
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      if (welded && mesh.position_vertex[v] != v) continue;
      double xyz[3];
      model_position(mesh, v, xyz);
      out << 'v';
      for (double x : xyz) {
        out << ' ';
        out.coordinate(x);
      }
      // Vertex colours as MeshLab and most readers take them: r g b in [0, 1] after x y z.
      if (!rgb.empty())
        for (int k = 0; k < 3; ++k) {
          out << ' ';
          out.number(float(rgb[3 * v + size_t(k)] / 255.0));
        }
      out.end_line();
    }
    if (has_vt)
      for (size_t v = 0; v < mesh.vertex_count(); ++v) add_line("vt", {uv[0]->values[v], uv[1]->values[v]});
    if (has_vn)
      for (size_t v = 0; v < mesh.vertex_count(); ++v)
        add_line("vn", {nrm[0]->values[v], nrm[1]->values[v], nrm[2]->values[v]});
    const uint32_t* t = mesh.triangles.data();
    uint32_t material = UINT32_MAX;  // of the previous triangle; "" needs no usemtl at the start
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      if (i % 3 == 0 && !tm.empty() && tm[i / 3] != material) {
        const std::string& name = mesh.materials[tm[i / 3]];
        if (material != UINT32_MAX || !name.empty()) out << (name.empty() ? std::string("usemtl\n") : "usemtl " + name + "\n");
        material = tm[i / 3];
      }
      out << (i % 3 == 0 ? "f " : " ");
      out.number(welded ? v_line[t[i]] : uint64_t(t[i]) + 1);
      if (has_vt || has_vn) {
        out << '/';
        if (has_vt) out.number(uint64_t(t[i]) + 1);
        if (has_vn) {
          out << '/';
          out.number(uint64_t(t[i]) + 1);
        }
      }
      if (i % 3 == 2) out.end_line();
    }
    out.flush();
  });
  write_material_files(path, mesh);
}

void write_obj(const std::string& path, const Mesh& mesh) { write_obj_colours(path, mesh, vertex_colour_bytes(mesh)); }

}  // namespace meshsal
