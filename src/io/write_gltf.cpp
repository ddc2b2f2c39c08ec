// meshsal: glTF 2.0 output (write_gltf in meshsal.h) through tinygltf's writer: one node
// and one mesh per level, the levels linked by MSFT_lod, the vertex data in one buffer.
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "core/utf8.h"
#include "io/atomic_write.h"
#include "io/colormap.h"
#include "io/gltf_assets.h"
#include "io/gltf_frame.h"
#include "io/mesh_io_internal.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// Appends `bytes` to the buffer as a new bufferView (4-byte aligned, as vertex data must
// be) and an accessor over it; returns the accessor's index.
struct Builder {
  tinygltf::Model& model;

  int view(const void* bytes, size_t size, int target) {
    std::vector<unsigned char>& data = model.buffers[0].data;
    data.resize((data.size() + 3) & ~size_t(3), 0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = data.size();
    v.byteLength = size;
    v.target = target;
    const unsigned char* p = static_cast<const unsigned char*>(bytes);
    data.insert(data.end(), p, p + size);
    model.bufferViews.push_back(v);
    return int(model.bufferViews.size()) - 1;
  }

  int accessor(const void* bytes, size_t count, int component, int type, size_t element, int target, bool normalized = false) {
    tinygltf::Accessor a;
    a.bufferView = view(bytes, count * element, target);
    a.byteOffset = 0;
    a.componentType = component;
    a.count = count;
    a.type = type;
    a.normalized = normalized;
    model.accessors.push_back(a);
    return int(model.accessors.size()) - 1;
  }
};

// glTF names custom vertex attributes with a leading underscore, in capitals by custom.
std::string custom_attribute_name(const std::string& name) {
  std::string out = "_";
  for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) ? char(std::toupper(static_cast<unsigned char>(c))) : '_';
  return out;
}

// Area-weighted vertex normals of `xyz` (used where an input normal is zero or missing in
// part: glTF requires unit normals).
std::vector<float> face_normals_at_vertices(const std::vector<float>& xyz, const std::vector<uint32_t>& tris) {
  std::vector<double> acc(xyz.size(), 0.0);
  for (size_t t = 0; t + 2 < tris.size(); t += 3) {
    const float* a = &xyz[3 * size_t(tris[t])];
    const float* b = &xyz[3 * size_t(tris[t + 1])];
    const float* c = &xyz[3 * size_t(tris[t + 2])];
    const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) acc[3 * size_t(tris[t + size_t(k)]) + size_t(j)] += n[j];
  }
  std::vector<float> out(xyz.size());
  for (size_t v = 0; v < out.size(); v += 3) {
    const double len = std::sqrt(acc[v] * acc[v] + acc[v + 1] * acc[v + 1] + acc[v + 2] * acc[v + 2]);
    for (int j = 0; j < 3; ++j) out[v + size_t(j)] = len > 0 ? float(acc[v + size_t(j)] / len) : (j == 2 ? 1.0f : 0.0f);
  }
  return out;
}

// Refuses a level whose per-vertex arrays do not match its mesh, or that has no triangle.
void check_level(const GltfLevel& level, const std::string& path) {
  const Mesh& mesh = *level.mesh;
  check_mesh(path, mesh);
  const size_t n = mesh.vertex_count();
  if (mesh.triangle_count() == 0) throw Error(path + ": cannot write: a glTF mesh needs at least one triangle");
  if (level.saliency && level.saliency->size() != n)
    throw Error(path + ": cannot write: " + std::to_string(level.saliency->size()) + " saliency values for " +
                std::to_string(n) + " vertices");
  if (level.is_point && level.is_point->size() != n)
    throw Error(path + ": cannot write: " + std::to_string(level.is_point->size()) + " mesh-point flags for " +
                std::to_string(n) + " vertices");
  for (const VertexAttribute& a : mesh.attributes)
    if (a.values.size() != n)
      throw Error(path + ": cannot write: attribute '" + a.name + "' has " + std::to_string(a.values.size()) +
                  " values for " + std::to_string(n) + " vertices");
}

// One level's vertex channels as they are added (the accessors in the order the file has
// them): the primitive's attributes, and the mesh's attributes already written as one.
struct Channels {
  tinygltf::Primitive prim;
  std::vector<const VertexAttribute*> used;
};

// Positions: the local floats as they are under a node at the origin (exact), or put
// back in the input's frame.
std::vector<float> level_positions(const Mesh& mesh, const Frame* inverse) {
  std::vector<float> xyz = mesh.positions;
  if (inverse) {
    for (size_t v = 0; v < mesh.vertex_count(); ++v) {
      double p[3], q[3];
      model_position(mesh, v, p);  // as read where unmoved: no rounding through the local floats
      transform_point(*inverse, p, q);
      for (int k = 0; k < 3; ++k) xyz[3 * v + size_t(k)] = float(q[k]);
    }
  }
  return xyz;
}

// POSITION, with the bounds glTF requires.
void add_positions(Builder& b, const std::vector<float>& xyz, size_t n, Channels& ch) {
  std::vector<double> lo(3, INFINITY), hi(3, -INFINITY);
  for (size_t v = 0; v < n; ++v)
    for (size_t k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(xyz[3 * v + k])), hi[k] = std::max(hi[k], double(xyz[3 * v + k]));
  const int a = b.accessor(xyz.data(), n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 12, kArrayBuffer);
  b.model.accessors[size_t(a)].minValues = lo;
  b.model.accessors[size_t(a)].maxValues = hi;
  ch.prim.attributes["POSITION"] = a;
}

// NORMAL from nx ny nz, unit length (the faces' normal where one is zero or not finite).
void add_normals(Builder& b, const Mesh& mesh, const std::vector<float>& xyz, const Frame* inverse, Channels& ch) {
  const size_t n = mesh.vertex_count();
  const VertexAttribute* nrm[3] = {find_attribute(mesh, "nx"), find_attribute(mesh, "ny"), find_attribute(mesh, "nz")};
  if (!nrm[0] || !nrm[1] || !nrm[2]) return;
  // Normals turn with the inverse transpose of the transform the positions took.
  const Frame nm = inverse ? normal_matrix(*inverse) : identity_frame();
  std::vector<float> normals(3 * n), fallback;
  for (size_t v = 0; v < n; ++v) {
    const double d[3] = {nrm[0]->values[v], nrm[1]->values[v], nrm[2]->values[v]};
    double w[3];
    transform_direction(nm, d, w);
    const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    if (!(len > 0) || !std::isfinite(len)) {
      if (fallback.empty()) fallback = face_normals_at_vertices(xyz, mesh.triangles);
      for (int k = 0; k < 3; ++k) normals[3 * v + size_t(k)] = fallback[3 * v + size_t(k)];
    } else {
      for (int k = 0; k < 3; ++k) normals[3 * v + size_t(k)] = float(w[k] / len);
    }
  }
  ch.prim.attributes["NORMAL"] = b.accessor(normals.data(), n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 12, kArrayBuffer);
  ch.used.insert(ch.used.end(), nrm, nrm + 3);
}

// TEXCOORD_<set> from each texture-coordinate set (attribute_role: u v, s t, texture_u
// texture_v for set 0; u1 v1 .. u7 v7), the first pair found of each set.
void add_texcoords(Builder& b, const Mesh& mesh, Channels& ch) {
  const size_t n = mesh.vertex_count();
  for (int set = 0; set < 8; ++set) {
    const VertexAttribute* uv_pair[2] = {nullptr, nullptr};
    for (const VertexAttribute& a : mesh.attributes) {
      const AttributeRole r = attribute_role(a.name);
      if (r.kind == AttributeKind::TexCoord && r.set == set && !uv_pair[r.component]) uv_pair[r.component] = &a;
    }
    if (!uv_pair[0] || !uv_pair[1]) continue;
    std::vector<float> uv(2 * n);
    for (size_t v = 0; v < n; ++v) uv[2 * v] = uv_pair[0]->values[v], uv[2 * v + 1] = 1.0f - uv_pair[1]->values[v];  // glTF's v runs down
    ch.prim.attributes["TEXCOORD_" + std::to_string(set)] =
        b.accessor(uv.data(), n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 8, kArrayBuffer);
    ch.used.push_back(uv_pair[0]), ch.used.push_back(uv_pair[1]);
  }
}

// COLOR_0: the saliency on the pictures' colour scale, else the input's colours. glTF's
// vertex colours are linear (the spec): our sRGB bytes go in converted, 16 bits a channel
// so that reading them back gives the same bytes. S goes as _SALIENCY: the level's, else
// S carried on the mesh (kSaliencyAttribute, e.g. read from a saliency PLY or a glTF's
// _SALIENCY).
void add_saliency_and_colours(Builder& b, const GltfLevel& level, Channels& ch) {
  const Mesh& mesh = *level.mesh;
  const size_t n = mesh.vertex_count();
  const VertexAttribute* rgba[4] = {find_attribute(mesh, "red"), find_attribute(mesh, "green"), find_attribute(mesh, "blue"),
                                    find_attribute(mesh, "alpha")};
  std::vector<uint8_t> colour(4 * n, 255);
  if (level.saliency) {
    const std::vector<uint8_t> rgb = colormap_values(*level.saliency, level.is_point ? *level.is_point : referenced_vertices(mesh),
                                                     level.range ? *level.range : ColorRange());
    for (size_t v = 0; v < n; ++v) std::copy_n(&rgb[3 * v], 3, &colour[4 * v]);
    ch.prim.attributes["_SALIENCY"] = [&] {
      std::vector<float> s(level.saliency->begin(), level.saliency->end());
      return b.accessor(s.data(), n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 4, kArrayBuffer);
    }();
  } else if (rgba[0] && rgba[1] && rgba[2]) {
    for (size_t v = 0; v < n; ++v)
      for (int k = 0; k < 4; ++k)
        if (rgba[k]) colour[4 * v + size_t(k)] = uint8_t(std::clamp(std::nearbyint(double(rgba[k]->values[v])), 0.0, 255.0));
    ch.used.insert(ch.used.end(), rgba, rgba + 4);
  }
  // S given beside the mesh replaces the S it carries.
  if (const VertexAttribute* carried = find_attribute(mesh, kSaliencyAttribute)) {
    if (!level.saliency)
      ch.prim.attributes["_SALIENCY"] = b.accessor(carried->values.data(), n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 4, kArrayBuffer);
    ch.used.push_back(carried);
  }
  if (level.saliency || (rgba[0] && rgba[1] && rgba[2])) {
    uint16_t table[256];
    for (int c = 0; c < 256; ++c) table[c] = uint16_t(std::nearbyint(srgb_to_linear(c / 255.0) * 65535.0));
    std::vector<uint16_t> linear(4 * n);
    for (size_t i = 0; i < linear.size(); ++i)
      linear[i] = i % 4 == 3 ? uint16_t(colour[i] * 257) : table[colour[i]];  // alpha is linear already
    ch.prim.attributes["COLOR_0"] =
        b.accessor(linear.data(), n, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, 8, kArrayBuffer, true);
  }
}

// Every other attribute as a custom float channel.
void add_custom_attributes(Builder& b, const Mesh& mesh, Channels& ch) {
  for (const VertexAttribute& a : mesh.attributes) {
    if (std::find(ch.used.begin(), ch.used.end(), &a) != ch.used.end()) continue;
    const std::string name = custom_attribute_name(a.name);
    if (ch.prim.attributes.count(name)) continue;
    ch.prim.attributes[name] = b.accessor(a.values.data(), mesh.vertex_count(), TINYGLTF_COMPONENT_TYPE_FLOAT,
                                          TINYGLTF_TYPE_SCALAR, 4, kArrayBuffer);
  }
}

// Triangles, one primitive per material (in the order of the material slots), each with
// the vertex channels of `prim`.
tinygltf::Mesh level_primitives(Builder& b, const GltfLevel& level, const tinygltf::Primitive& prim,
                                const std::string& path) {
  const Mesh& mesh = *level.mesh;
  tinygltf::Mesh gm;
  gm.name = level.name;
  const std::vector<uint32_t>& tm = mesh.triangle_material;
  if (!tm.empty() && tm.size() != mesh.triangle_count())
    throw Error(path + ": cannot write: triangle_material has " + std::to_string(tm.size()) + " entries for " +
                std::to_string(mesh.triangle_count()) + " triangles");
  const size_t slots = tm.empty() ? 1 : mesh.materials.size();
  for (size_t slot = 0; slot < slots; ++slot) {
    std::vector<uint32_t> idx;
    for (size_t t = 0; t < mesh.triangle_count(); ++t)
      if (tm.empty() || tm[t] == slot) idx.insert(idx.end(), &mesh.triangles[3 * t], &mesh.triangles[3 * t] + 3);
    if (idx.empty()) continue;
    tinygltf::Primitive p = prim;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    p.indices = b.accessor(idx.data(), idx.size(), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, 4, kElementArrayBuffer);
    if (!tm.empty()) {
      const GltfAssets* assets = mesh.gltf_assets.get();
      p.material = assets && slot < assets->slot_material.size() ? assets->slot_material[slot] : int(slot);
      if (p.material >= int(b.model.materials.size())) p.material = -1;
    }
    gm.primitives.push_back(std::move(p));
  }
  if (gm.primitives.empty()) throw Error(path + ": cannot write: triangle_material names no material slot");
  return gm;
}

// One level: its mesh (with primitives per material), returning the mesh's index. The
// accessors go in this order: positions, normals, texture coordinates, S, colours, the
// other attributes, then each primitive's indices.
int add_level(Builder& b, const GltfLevel& level, const Frame* inverse, const std::string& path) {
  const Mesh& mesh = *level.mesh;
  check_level(level, path);
  Channels ch;
  const std::vector<float> xyz = level_positions(mesh, inverse);
  add_positions(b, xyz, mesh.vertex_count(), ch);
  add_normals(b, mesh, xyz, inverse, ch);
  add_texcoords(b, mesh, ch);
  add_saliency_and_colours(b, level, ch);
  add_custom_attributes(b, mesh, ch);
  b.model.meshes.push_back(level_primitives(b, level, ch.prim, path));
  return int(b.model.meshes.size()) - 1;
}

// The materials of the output: the glTF input's, carried over, or one plain material per
// named slot (an OBJ's usemtl names).
void add_materials(tinygltf::Model& model, const Mesh& mesh) {
  if (mesh.triangle_material.empty()) return;
  if (const GltfAssets* a = mesh.gltf_assets.get()) {
    model.materials = a->materials;
    model.textures = a->textures;
    model.samplers = a->samplers;
    model.images = a->images;
    // Each distinct image source once, as one bufferView the images that shared it share.
    std::vector<int> view_of(a->image_bytes.size(), -1);
    for (size_t i = 0; i < model.images.size(); ++i) {
      const int source = i < a->image_source.size() ? a->image_source[i] : -1;
      if (source < 0) continue;  // unread external file: its uri stays
      if (view_of[size_t(source)] < 0) {
        Builder b{model};
        const std::vector<unsigned char>& bytes = a->image_bytes[size_t(source)];
        view_of[size_t(source)] = b.view(bytes.data(), bytes.size(), 0);
      }
      model.images[i].bufferView = view_of[size_t(source)];
      model.images[i].uri.clear();
    }
    for (const std::string& e : a->extensions_used) model.extensionsUsed.push_back(e);
    for (const std::string& e : a->extensions_required) model.extensionsRequired.push_back(e);
    return;
  }
  for (const std::string& name : mesh.materials) {
    tinygltf::Material m;
    // glTF's JSON is UTF-8 (its writer throws on other bytes): an OBJ's usemtl name in
    // another encoding is written as its visible form, "caf\xe9".
    m.name = name.empty() ? "default" : valid_utf8(name) ? name : visible_text(name);
    model.materials.push_back(m);
  }
}

}  // namespace

std::string gltf_file_bytes(const std::string& path, const std::vector<GltfLevel>& levels, bool binary) {
  if (levels.empty()) throw Error(path + ": cannot write: no mesh given");
  for (const GltfLevel& l : levels)
    if (!l.mesh) throw Error(path + ": cannot write: a level without a mesh");
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "meshsal";
  model.buffers.resize(1);
  add_materials(model, *levels[0].mesh);
  Builder b{model};
  // The frame: the input's shared node transform; else the model's own coordinates as
  // floats under no transform, so that a reader that ignores nodes sees the model where the
  // PLY and OBJ put it; else, where floats would move the model's coordinates (the PLY
  // rule, positions_need_double: survey coordinates), a translation to the origin of the
  // local coordinates, whose floats stay exactly as computed.
  const Mesh& first = *levels[0].mesh;
  Frame frame = identity_frame(), inverse{};
  bool use_inverse = false;
  if (first.frame.size() == 16) {
    std::copy(first.frame.begin(), first.frame.end(), frame.begin());
    inverse = inverse_affine(frame);
    use_inverse = determinant3(frame) != 0 && std::isfinite(determinant3(frame));
    if (!use_inverse) frame = identity_frame();
  }
  if (!use_inverse && !positions_need_double(first)) {
    inverse = identity_frame();
    use_inverse = true;
  }
  std::vector<int> nodes;
  for (size_t i = 0; i < levels.size(); ++i) {
    GltfLevel level = levels[i];
    if (level.name.empty()) level.name = levels.size() == 1 ? "mesh" : "LOD" + std::to_string(i);
    const Mesh& m = *level.mesh;
    tinygltf::Node node;
    node.name = level.name;
    node.mesh = add_level(b, level, use_inverse ? &inverse : nullptr, path);
    if (use_inverse) {
      if (frame != identity_frame()) node.matrix.assign(frame.begin(), frame.end());
    } else if (m.origin[0] != 0 || m.origin[1] != 0 || m.origin[2] != 0) {
      node.translation = {m.origin[0], m.origin[1], m.origin[2]};
    }
    model.nodes.push_back(std::move(node));
    nodes.push_back(int(model.nodes.size()) - 1);
  }
  if (levels.size() > 1) {
    // MSFT_lod: the scene shows the finest level; its node lists the coarser ones in order.
    tinygltf::Value::Array ids;
    for (size_t i = 1; i < nodes.size(); ++i) ids.push_back(tinygltf::Value(nodes[i]));
    tinygltf::Value::Object lod;
    lod["ids"] = tinygltf::Value(ids);
    model.nodes[size_t(nodes[0])].extensions["MSFT_lod"] = tinygltf::Value(lod);
    model.extensionsUsed.push_back("MSFT_lod");
  }
  tinygltf::Scene scene;
  scene.nodes = {nodes[0]};
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/!binary, binary))
    throw Error(path + ": cannot write: the glTF writer failed");
  return out.str();
}

void write_gltf(const std::string& path, const std::vector<GltfLevel>& levels) {
  const std::string format = mesh_output_format(path);
  const bool binary = format == ".glb";
  if (!binary && format != ".gltf") throw Error(path + ": cannot write: glTF output ends in .glb or .gltf");
  const std::string bytes = gltf_file_bytes(path, levels, binary);
  write_file_atomically(path, [&](std::FILE* f) { write_all(f, bytes.data(), bytes.size(), path); });
}

void write_gltf(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency) {
  GltfLevel level;
  level.mesh = &mesh;
  level.saliency = saliency.empty() ? nullptr : &saliency;
  write_gltf(path, {level});
}

}  // namespace meshsal
