// meshsal: glTF 2.0 input (.gltf with its buffers, .glb) through tinygltf (Debian's
// libtinygltf-dev). tinygltf parses the JSON and the buffers; everything read from them
// (accessors, strides, sparse substitutions, indices, the node tree) is checked here before
// it is used, so a hostile file gives an Error, never a read out of bounds.
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "io/gltf_assets.h"
#include "io/gltf_frame.h"
#include "io/json_nesting.h"
#include "io/mesh_io_internal.h"
#include "io/model_reference.h"
#include "io/read_bytes.h"
#include "io/seam_twins.h"
#include "io/text_scan.h"

namespace meshsal {
namespace {

// What tinygltf may read besides the file itself: the files its buffer and image URIs name,
// under the rule of io/model_reference.h (in the model's folder or below, regular files),
// all of them together within one budget; none at all when the glTF came from memory.
struct FileAccess {
  std::string folder;   // the model's folder; "" = loaded from memory
  uint64_t budget = 0;  // bytes left for the model's external files together
  // The first reference refused, in our words: the load fails with it even where tinygltf
  // only warns (an image it cannot read), and tinygltf's own message would name the
  // path it tried and, for a buffer, the size it found.
  std::string refusal;
};

// Every name "exists": read_whole_file then says what is wrong with it.
bool file_exists(const std::string&, void*) { return true; }

std::string expand_path(const std::string& path, void*) { return path; }  // no shell expansion

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  FileAccess& access = *static_cast<FileAccess*>(user);
  // tinygltf passes the model's folder joined with the percent-decoded URI (JoinPath).
  const std::string prefix = access.folder.empty() || access.folder.back() == '/' ? access.folder : access.folder + "/";
  const std::string reference = path.compare(0, prefix.size(), prefix) == 0 ? path.substr(prefix.size()) : path;
  try {
    if (access.folder.empty())
      throw Error(quoted(reference, 200) + ": refers to an external file (only a glTF file on disk may; this one came from memory)");
    *out = read_model_reference(access.folder, reference, /*uri=*/true, access.budget);
    access.budget -= out->size();
    return true;
  } catch (const Error& e) {
    if (access.refusal.empty()) access.refusal = e.what();
    if (err) *err += "refused\n";
    return false;
  }
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed while loading\n";
  return false;
}

// Images are kept as bytes (never decoded: saliency needs no texture, and a carried
// texture is written as it was read). One in a bufferView is not touched here: tinygltf
// 2.7 hands its bytes over without checking the view against its buffer, so carry_assets
// copies those after checking (view_span).
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0) image->image.assign(bytes, bytes + std::max(size, 0));
  image->as_is = true;
  return true;
}

[[noreturn]] void fail(const std::string& what) { throw Error(what); }

size_t component_bytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

size_t type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
  }
}

// One component as a double: floats as they are, integers as they are or, when
// `normalized`, mapped to [0, 1] (unsigned) or [-1, 1] (signed) as the glTF spec says.
double component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
    case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t c; std::memcpy(&c, p, 1); return normalized ? std::max(c / 127.0, -1.0) : c; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t c; std::memcpy(&c, p, 2); return normalized ? std::max(c / 32767.0, -1.0) : c; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t c; std::memcpy(&c, p, 2); return normalized ? c / 65535.0 : c; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t c; std::memcpy(&c, p, 4); return normalized ? c / 4294967295.0 : c; }
  }
  return 0;
}

// The bytes of bufferView `index` that `count` elements of `element` bytes at `offset` with
// `stride` (0 = packed) occupy, checked to lie inside it; returns the first element.
const unsigned char* view_span(const tinygltf::Model& model, int index, size_t offset, size_t count,
                               size_t element, size_t stride, const std::string& what, size_t* step) {
  if (index < 0 || size_t(index) >= model.bufferViews.size()) fail(what + ": bufferView " + std::to_string(index) + " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[size_t(index)];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) fail(what + ": its bufferView names no buffer");
  const std::vector<unsigned char>& data = model.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail(what + ": bufferView " + std::to_string(index) + " runs past the end of its buffer");
  if (stride == 0) stride = element;
  if (stride < element) fail(what + ": byteStride " + std::to_string(stride) + " is smaller than an element");
  *step = stride;
  if (count == 0) return data.data() + view.byteOffset;
  // offset + (count - 1) * stride + element <= byteLength, without overflow.
  const unsigned __int128 end = (unsigned __int128)offset + (unsigned __int128)(count - 1) * stride + element;
  if (end > view.byteLength) fail(what + ": " + std::to_string(count) + " elements run past the end of bufferView " + std::to_string(index));
  return data.data() + view.byteOffset + offset;
}

// Where an accessor's data lies, checked without reading it: its bufferView span, and
// for a sparse one its indices' and values' spans. Nothing is sized by a count before this
// says the file holds that count: an accessor without a bufferView (zeros, then sparse
// substitutions) may not declare more elements than the file's bytes could hold dense,
// so that a 5 KB file cannot ask for gigabytes of zeros.
struct AccessorData {
  const tinygltf::Accessor* accessor = nullptr;
  size_t bytes = 0;     // per component
  size_t element = 0;   // bytes per element
  const unsigned char* base = nullptr;  // first element (null: no bufferView, zeros)
  size_t step = 0;
  size_t sparse = 0;    // substitutions
  int index_type = 0;
  const unsigned char* indices = nullptr;
  const unsigned char* values = nullptr;
  size_t index_step = 0, value_step = 0;
};

AccessorData locate_accessor(const tinygltf::Model& model, int index, size_t components, const std::string& what,
                             uint64_t input_bytes) {
  if (index < 0 || size_t(index) >= model.accessors.size()) fail(what + ": accessor " + std::to_string(index) + " does not exist");
  const tinygltf::Accessor& a = model.accessors[size_t(index)];
  AccessorData d;
  d.accessor = &a;
  d.bytes = component_bytes(a.componentType);
  if (d.bytes == 0) fail(what + ": unsupported component type " + std::to_string(a.componentType));
  if (type_components(a.type) != components) fail(what + ": expected " + std::to_string(components) + " components per element");
  d.element = d.bytes * components;
  if (a.bufferView >= 0) {
    const size_t stride = size_t(a.bufferView) < model.bufferViews.size() ? model.bufferViews[size_t(a.bufferView)].byteStride : 0;
    d.base = view_span(model, a.bufferView, a.byteOffset, a.count, d.element, stride, what, &d.step);
  } else if (!a.sparse.isSparse) {
    fail(what + ": accessor " + std::to_string(index) + " has no data (no bufferView and not sparse)");
  } else if ((unsigned __int128)a.count * d.element > input_bytes) {
    fail(what + ": accessor " + std::to_string(index) + " declares " + std::to_string(a.count) +
         " elements with no bufferView, more than the file's " + std::to_string(input_bytes) + " bytes could hold");
  }
  if (a.sparse.isSparse) {
    d.sparse = size_t(std::max(a.sparse.count, 0));
    if (a.sparse.count < 1 || d.sparse > a.count) fail(what + ": sparse count " + std::to_string(a.sparse.count) + " out of range");
    d.index_type = a.sparse.indices.componentType;
    const size_t ibytes = d.index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || d.index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                                  d.index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT
                              ? component_bytes(d.index_type) : 0;
    if (ibytes == 0) fail(what + ": sparse indices of an unsupported type");
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
      fail(what + ": a negative sparse byteOffset");
    d.indices = view_span(model, a.sparse.indices.bufferView, size_t(a.sparse.indices.byteOffset), d.sparse, ibytes, 0,
                          what + " (sparse indices)", &d.index_step);
    d.values = view_span(model, a.sparse.values.bufferView, size_t(a.sparse.values.byteOffset), d.sparse, d.element, 0,
                         what + " (sparse values)", &d.value_step);
  }
  return d;
}

// An accessor's values as doubles, `components` per element (checked against its type),
// sparse substitutions applied. `count`: the element count it must have (POSITION's, for
// the other vertex attributes), checked before anything is allocated; SIZE_MAX: any.
std::vector<double> read_accessor(const tinygltf::Model& model, int index, size_t components, const std::string& what,
                                  uint64_t input_bytes, size_t count = SIZE_MAX) {
  if (count != SIZE_MAX && index >= 0 && size_t(index) < model.accessors.size() && model.accessors[size_t(index)].count != count)
    fail(what + ": " + std::to_string(model.accessors[size_t(index)].count) + " elements where POSITION has " + std::to_string(count));
  const AccessorData d = locate_accessor(model, index, components, what, input_bytes);
  const tinygltf::Accessor& a = *d.accessor;
  std::vector<double> out(a.count * components, 0.0);
  if (d.base)
    for (size_t i = 0; i < a.count; ++i)
      for (size_t c = 0; c < components; ++c)
        out[i * components + c] = component(d.base + i * d.step + c * d.bytes, a.componentType, a.normalized);
  for (size_t k = 0; k < d.sparse; ++k) {
    const double target = component(d.indices + k * d.index_step, d.index_type, false);
    if (target >= double(a.count)) fail(what + ": sparse index " + std::to_string(uint64_t(target)) + " out of range");
    for (size_t c = 0; c < components; ++c)
      out[size_t(target) * components + c] = component(d.values + k * d.value_step + c * d.bytes, a.componentType, a.normalized);
  }
  return out;
}

// A node's own transform (matrix, or translation * rotation * scale), column-major.
Frame node_transform(const tinygltf::Node& node, const std::string& what) {
  Frame m = identity_frame();
  if (node.matrix.size() == 16) {
    std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
  } else {
    if (!node.matrix.empty()) fail(what + ": a matrix needs 16 numbers");
    std::array<double, 3> t{0, 0, 0}, s{1, 1, 1};
    std::array<double, 4> q{0, 0, 0, 1};
    if (!node.translation.empty()) { if (node.translation.size() != 3) fail(what + ": translation needs 3 numbers"); std::copy_n(node.translation.begin(), 3, t.begin()); }
    if (!node.scale.empty()) { if (node.scale.size() != 3) fail(what + ": scale needs 3 numbers"); std::copy_n(node.scale.begin(), 3, s.begin()); }
    if (!node.rotation.empty()) { if (node.rotation.size() != 4) fail(what + ": rotation needs 4 numbers"); std::copy_n(node.rotation.begin(), 4, q.begin()); }
    m = trs_frame(t.data(), q.data(), s.data());
  }
  for (double v : m)
    if (!std::isfinite(v)) fail(what + ": a transform with a non-finite number");
  return m;
}

struct Instance {
  int mesh;
  Frame world;
};

// The mesh instances of the default scene (scene 0 when none is named; every root node
// when the file has no scene), each with its world transform. The node graph must be a
// tree (the spec's rule): a node reached twice is refused, which also stops cycles.
std::vector<Instance> scene_instances(const tinygltf::Model& model) {
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(s) >= model.scenes.size()) fail("scene " + std::to_string(s) + " does not exist");
    roots = model.scenes[size_t(s)].nodes;
  } else {
    std::vector<char> child(model.nodes.size(), 0);
    for (const tinygltf::Node& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = 1;
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (!child[i]) roots.push_back(int(i));
  }
  std::vector<Instance> out;
  std::vector<char> seen(model.nodes.size(), 0);
  std::vector<std::pair<int, Frame>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, identity_frame()});
  while (!stack.empty()) {
    const auto [index, parent] = stack.back();
    stack.pop_back();
    const std::string what = "node " + std::to_string(index);
    if (index < 0 || size_t(index) >= model.nodes.size()) fail(what + " does not exist");
    if (seen[size_t(index)]) fail(what + " is reached twice (the node hierarchy must be a tree)");
    seen[size_t(index)] = 1;
    const tinygltf::Node& node = model.nodes[size_t(index)];
    if (node.extensions.count("EXT_mesh_gpu_instancing"))
      fail(what + ": uses EXT_mesh_gpu_instancing, which meshsal does not read");
    const Frame world = multiply(parent, node_transform(node, what));
    if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model.meshes.size()) fail(what + ": mesh " + std::to_string(node.mesh) + " does not exist");
      out.push_back({node.mesh, world});
    }
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
  }
  return out;
}

// A vertex channel read with LoadOptions::attributes: a glTF attribute and the Mesh
// attributes it fills, under the names every reader uses (attribute_role): NORMAL as nx ny
// nz, TEXCOORD_0 as u v and TEXCOORD_n as un vn, COLOR_0 as red green blue alpha (sRGB
// bytes), _SALIENCY as quality (S), any other scalar _NAME as name in lower case.
struct Channel {
  std::string semantic;
  std::vector<VertexAttribute> attributes;
};

// The channels of the primitives: every one that some primitive has (a primitive without
// it gets neutral values: a zero normal, which a writer replaces by the faces' normal, UV
// 0 0, white, 0), so that a material that needs TEXCOORD_n on one primitive keeps it. What
// is not read is named in `skipped`.
std::vector<Channel> vertex_channels(const tinygltf::Model& model, const std::vector<Instance>& instances,
                                     std::set<std::string>* skipped) {
  std::set<std::string> semantics;
  for (const Instance& in : instances)
    for (const tinygltf::Primitive& p : model.meshes[size_t(in.mesh)].primitives)
      for (const auto& [semantic, accessor] : p.attributes)
        if (semantic != "POSITION") {
          const bool scalar = accessor >= 0 && size_t(accessor) < model.accessors.size() &&
                              model.accessors[size_t(accessor)].type == TINYGLTF_TYPE_SCALAR;
          const bool texcoord = semantic.size() == 10 && semantic.compare(0, 9, "TEXCOORD_") == 0 && semantic[9] >= '0' && semantic[9] <= '7';
          if (semantic == "NORMAL" || semantic == "COLOR_0" || texcoord || (semantic[0] == '_' && scalar && semantic.size() > 1))
            semantics.insert(semantic);
          else
            skipped->insert("vertex attribute '" + semantic + "'");
        }
  std::vector<Channel> out;
  std::set<std::string> taken;
  auto add = [&](const std::string& semantic, std::vector<std::string> names) {
    if (!semantics.count(semantic)) return;
    for (const std::string& n : names)
      if (taken.count(n)) {
        skipped->insert("vertex attribute '" + semantic + "' (its name '" + n + "' is taken)");
        return;
      }
    Channel c{semantic, {}};
    for (std::string& n : names) taken.insert(n), c.attributes.push_back({std::move(n), {}});
    out.push_back(std::move(c));
  };
  add("NORMAL", {"nx", "ny", "nz"});
  add("TEXCOORD_0", {"u", "v"});
  for (char set = '1'; set <= '7'; ++set) add(std::string("TEXCOORD_") + set, {std::string("u") + set, std::string("v") + set});
  add("COLOR_0", {"red", "green", "blue", "alpha"});
  add("_SALIENCY", {kSaliencyAttribute});
  for (const std::string& semantic : semantics)
    if (semantic[0] == '_' && semantic != "_SALIENCY") {
      std::string name = semantic.substr(1);
      std::transform(name.begin(), name.end(), name.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
      add(semantic, {name});
    }
  return out;
}

// Appends one primitive's values of `c` (nv vertices) to its attributes, converted to the
// Mesh's conventions, or neutral values where the primitive lacks the channel.
void read_channel(const tinygltf::Model& model, const tinygltf::Primitive& p, Channel& c, size_t nv, const Frame& normal_frame,
                  const std::string& what, uint64_t input_bytes) {
  const auto found = p.attributes.find(c.semantic);
  std::vector<VertexAttribute>& a = c.attributes;
  if (found == p.attributes.end()) {
    const float neutral = c.semantic == "COLOR_0" ? 255.0f : 0.0f;
    for (VertexAttribute& x : a) x.values.insert(x.values.end(), nv, neutral);
    return;
  }
  const std::string where = what + " " + c.semantic;
  if (c.semantic == "NORMAL") {
    const std::vector<double> n = read_accessor(model, found->second, 3, where, input_bytes, nv);
    for (size_t v = 0; v < nv; ++v) {
      double w[3];
      transform_direction(normal_frame, &n[3 * v], w);
      const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      for (size_t k = 0; k < 3; ++k) a[k].values.push_back(float(len > 0 ? w[k] / len : w[k]));
    }
  } else if (c.semantic.compare(0, 9, "TEXCOORD_") == 0) {
    const std::vector<double> t = read_accessor(model, found->second, 2, where, input_bytes, nv);
    // glTF's v runs down the image, OBJ's (and every other loader's) up.
    for (size_t v = 0; v < nv; ++v) a[0].values.push_back(float(t[2 * v])), a[1].values.push_back(float(1.0 - t[2 * v + 1]));
  } else if (c.semantic == "COLOR_0") {
    const int acc = found->second;
    const size_t comps = acc >= 0 && size_t(acc) < model.accessors.size() && model.accessors[size_t(acc)].type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    const std::vector<double> col = read_accessor(model, acc, comps, where, input_bytes, nv);
    for (size_t v = 0; v < nv; ++v)
      for (size_t k = 0; k < 4; ++k) {
        // Linear in glTF; sRGB bytes in meshsal (alpha stays linear).
        const double x = std::clamp(k < comps ? col[comps * v + k] : 1.0, 0.0, 1.0);
        a[k].values.push_back(float(std::nearbyint((k == 3 ? x : linear_to_srgb(x)) * 255.0)));
      }
  } else {
    const std::vector<double> x = read_accessor(model, found->second, 1, where, input_bytes, nv);
    for (double value : x) a[0].values.push_back(float(value));
  }
}

// Extensions of the geometry that meshsal refuses by name (it cannot decode them).
bool unreadable_extension(const std::string& ext) {
  return ext == "KHR_draco_mesh_compression" || ext == "EXT_meshopt_compression" || ext == "KHR_meshopt_compression" ||
         ext == "EXT_mesh_gpu_instancing";
}

// Extensions that live in the materials, textures and images meshsal carries over
// unchanged: the output uses them as the input did.
bool carried_extension(const std::string& ext) {
  return ext.rfind("KHR_materials_", 0) == 0 || ext == "KHR_texture_transform" || ext == "KHR_texture_basisu" ||
         ext == "EXT_texture_webp" || ext == "EXT_texture_avif";
}

// A reader must refuse a file that requires an extension it does not support (glTF 2.0,
// 3.12): those meshsal reads (quantised attributes) or carries are known.
bool known_required_extension(const std::string& ext) {
  return ext == "KHR_mesh_quantization" || carried_extension(ext);
}

// The image's file type from its first bytes (a bufferView image must name it).
std::string image_mime(const std::vector<unsigned char>& b) {
  if (b.size() >= 8 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G') return "image/png";
  if (b.size() >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff) return "image/jpeg";
  if (b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 && std::memcmp(b.data() + 8, "WEBP", 4) == 0) return "image/webp";
  if (b.size() >= 12 && std::memcmp(b.data() + 4, "ftyp", 4) == 0) return "image/ktx2";
  return "";
}

// `index` names one of `count` items (-1: none).
bool dangling(int index, size_t count) { return index < -1 || (index >= 0 && size_t(index) >= count); }

// Old texture index -> new (-1: dropped), with why a dropped one is gone.
struct TextureMap {
  std::vector<int> to;
  std::string why(int index) const {
    return index >= 0 && size_t(index) < to.size() ? "which has no image left" : "which does not exist";
  }
  int operator()(int index) const { return index >= 0 && size_t(index) < to.size() ? to[size_t(index)] : -1; }
};

// A material's texture references (the index of a textureInfo) inside its extensions,
// e.g. KHR_materials_clearcoat's clearcoatTexture: renumbered, and removed with a note
// where the texture is gone. Values nest no deeper than the JSON they came from
// (kMaxJsonNesting), so the recursion is bounded.
tinygltf::Value renumber_textures(const tinygltf::Value& v, const TextureMap& map, const std::string& where,
                                  std::set<std::string>* notes) {
  if (!v.IsObject()) return v;
  tinygltf::Value::Object o = v.Get<tinygltf::Value::Object>();
  for (auto it = o.begin(); it != o.end();) {
    const bool info = it->first.size() > 7 && it->first.compare(it->first.size() - 7, 7, "Texture") == 0 &&
                      it->second.IsObject() && it->second.Get("index").IsInt();
    if (!info) {
      it->second = renumber_textures(it->second, map, where, notes);
      ++it;
      continue;
    }
    const int old = it->second.Get("index").Get<int>();
    if (map(old) < 0) {
      notes->insert(where + "'s " + it->first + " names texture " + std::to_string(old) + ", " + map.why(old) + ": dropped");
      it = o.erase(it);
      continue;
    }
    tinygltf::Value::Object textureInfo = it->second.Get<tinygltf::Value::Object>();
    textureInfo["index"] = tinygltf::Value(map(old));
    it->second = tinygltf::Value(std::move(textureInfo));
    ++it;
  }
  return tinygltf::Value(std::move(o));
}

// References between the carried materials, textures, images and samplers: each one
// naming nothing is dropped with a note, so that no output is invalid glTF. A texture left
// with no image (its source and its extensions' sources all dangling) is removed and the
// others renumbered (glTF has no empty texture).
void drop_dangling_references(tinygltf::Model& model, std::set<std::string>* notes) {
  const size_t images = model.images.size(), samplers = model.samplers.size();
  TextureMap map;
  std::vector<tinygltf::Texture> kept;
  for (size_t t = 0; t < model.textures.size(); ++t) {
    tinygltf::Texture& tex = model.textures[t];
    const std::string where = "texture " + std::to_string(t);
    if (dangling(tex.source, images)) notes->insert(where + " names image " + std::to_string(tex.source) + ", which does not exist: dropped"), tex.source = -1;
    if (dangling(tex.sampler, samplers)) notes->insert(where + " names sampler " + std::to_string(tex.sampler) + ", which does not exist: dropped"), tex.sampler = -1;
    for (auto it = tex.extensions.begin(); it != tex.extensions.end();) {
      const tinygltf::Value& source = it->second.Get("source");
      if (source.IsInt() && dangling(source.Get<int>(), images)) {
        notes->insert(where + "'s " + it->first + " names image " + std::to_string(source.Get<int>()) + ", which does not exist: dropped");
        it = tex.extensions.erase(it);
      } else {
        ++it;
      }
    }
    if (tex.source < 0 && tex.extensions.empty()) {
      map.to.push_back(-1);
      continue;
    }
    map.to.push_back(int(kept.size()));
    kept.push_back(std::move(tex));
  }
  model.textures = std::move(kept);
  for (size_t m = 0; m < model.materials.size(); ++m) {
    tinygltf::Material& mat = model.materials[m];
    const std::string where = "material " + std::to_string(m);
    auto renumber = [&](int& index, const char* name) {
      if (index == -1) return;
      if (map(index) < 0) notes->insert(where + "'s " + name + " names texture " + std::to_string(index) + ", " + map.why(index) + ": dropped");
      index = map(index);
    };
    renumber(mat.pbrMetallicRoughness.baseColorTexture.index, "baseColorTexture");
    renumber(mat.pbrMetallicRoughness.metallicRoughnessTexture.index, "metallicRoughnessTexture");
    renumber(mat.normalTexture.index, "normalTexture");
    renumber(mat.occlusionTexture.index, "occlusionTexture");
    renumber(mat.emissiveTexture.index, "emissiveTexture");
    for (auto& [name, value] : mat.extensions) value = renumber_textures(value, map, where + "'s " + name, notes);
  }
}

// The input's materials and what they use, for write_gltf (GltfAssets). Each image's bytes
// are taken once per distinct source: images that share a bufferView share one copy.
std::shared_ptr<const GltfAssets> carry_assets(tinygltf::Model& model, const std::map<int, uint32_t>& material_slot,
                                               std::set<std::string>* notes) {
  if (model.materials.empty()) return nullptr;
  drop_dangling_references(model, notes);
  auto a = std::make_shared<GltfAssets>();
  std::map<int, int> source_of_view;
  for (tinygltf::Image& im : model.images) {
    int source = -1;
    if (im.bufferView >= 0) {
      const auto known = source_of_view.find(im.bufferView);
      if (known != source_of_view.end()) {
        source = known->second;
      } else {
        size_t step = 0;
        const size_t len = size_t(im.bufferView) < model.bufferViews.size() ? model.bufferViews[size_t(im.bufferView)].byteLength : 0;
        const unsigned char* p = view_span(model, im.bufferView, 0, len ? 1 : 0, len, 0, "image '" + im.name + "'", &step);
        source = int(a->image_bytes.size());
        a->image_bytes.emplace_back(p, p + len);
        source_of_view[im.bufferView] = source;
      }
    } else if (!im.image.empty()) {
      source = int(a->image_bytes.size());
      a->image_bytes.push_back(std::move(im.image));
    }
    im.image.clear();
    im.image.shrink_to_fit();
    if (source >= 0) {
      im.uri.clear();
      if (im.mimeType.empty()) im.mimeType = image_mime(a->image_bytes[size_t(source)]);
      if (im.mimeType.empty()) im.mimeType = "image/png";
    }
    im.bufferView = -1;
    a->image_source.push_back(source);
  }
  a->materials = std::move(model.materials);
  a->textures = std::move(model.textures);
  a->images = std::move(model.images);
  a->samplers = std::move(model.samplers);
  for (const std::string& e : model.extensionsUsed)
    if (carried_extension(e)) a->extensions_used.push_back(e);
  for (const std::string& e : model.extensionsRequired)
    if (carried_extension(e)) a->extensions_required.push_back(e);
  a->slot_material.assign(material_slot.size(), -1);
  for (const auto& [material, slot] : material_slot) a->slot_material[slot] = material;
  return a;
}

// The JSON of a glTF file: the whole text, or a GLB's first chunk (clipped to the bytes
// there are; tinygltf checks the header itself).
std::string_view json_text(std::string_view bytes, bool binary) {
  if (!binary) return bytes;
  if (bytes.size() < 20) return {};
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return bytes.substr(20, length);
}

// tinygltf's first error line, without what it says of a file's size (a refused or
// mismatched external file must not tell its size).
std::string loader_error(std::string err) {
  while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
  const size_t nl = err.find('\n');
  if (nl != std::string::npos) err.resize(nl);
  if (err.rfind("File size mismatch", 0) == 0) return "an external buffer's file is not as long as its byteLength";
  return err;
}

// The glTF parsed by tinygltf (external files read under FileAccess's rule), refused with
// our message where it is not valid or requires an extension meshsal does not honour.
tinygltf::Model parse_model(std::string_view bytes, bool binary, const std::string& folder, uint64_t limit) {
  // No parser recurses into JSON nested deeper than we read (tinygltf's conversion of
  // extras and extensions recurses once per level).
  if (json_nesting(json_text(bytes, binary)) > kMaxJsonNesting)
    fail("its JSON nests deeper than " + std::to_string(kMaxJsonNesting) + " levels, the most meshsal reads");
  tinygltf::TinyGLTF loader;
  FileAccess access{folder, limit ? limit : kNoHeaderLimitBytes, ""};
  loader.SetFsCallbacks({&file_exists, &expand_path, &read_whole_file, &write_whole_file, &access});
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                       unsigned(std::min<size_t>(bytes.size(), UINT32_MAX)), folder)
                         : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                                      unsigned(std::min<size_t>(bytes.size(), UINT32_MAX)), folder);
  if (!access.refusal.empty()) fail(access.refusal);
  if (!ok) {
    // A compressed file (gltfpack -cc, Draco) fails tinygltf's buffer checks before its
    // extensions are known (its fallback buffer has no data): name the extension instead.
    const std::string_view json = json_text(bytes, binary);
    for (const char* ext : {"EXT_meshopt_compression", "KHR_meshopt_compression", "KHR_draco_mesh_compression"})
      if (json.find(ext) != std::string_view::npos)
        fail(std::string("uses the extension ") + ext +
             ", which meshsal does not read (decompress it first, e.g. with gltfpack -noq)");
    fail("not a valid glTF file: " + loader_error(err));
  }
  for (const std::string& ext : model.extensionsRequired) {
    if (unreadable_extension(ext))
      fail("requires the extension " + ext + ", which meshsal does not read (decompress it first, e.g. with gltfpack -noq)");
    if (!known_required_extension(ext))
      fail("requires the extension " + quoted(ext, 80) + ", which meshsal does not know (a reader must refuse what it cannot honour)");
  }
  return model;
}

// The memory bound: instancing lets a small file name a large mesh many times, so the
// vertices and indices to build are counted and held to the other loaders' rule first.
// Each accessor's count is first held to the bytes the file has for it (locate_accessor),
// so a count no file could back is named as such, not as instancing.
void check_scene_size(const tinygltf::Model& model, const std::vector<Instance>& instances, uint64_t input_bytes) {
  unsigned __int128 need = 0;
  for (const Instance& in : instances)
    for (size_t pi = 0; pi < model.meshes[size_t(in.mesh)].primitives.size(); ++pi) {
      const tinygltf::Primitive& p = model.meshes[size_t(in.mesh)].primitives[pi];
      const std::string what = "mesh " + std::to_string(in.mesh) + " primitive " + std::to_string(pi);
      const auto pos = p.attributes.find("POSITION");
      if (pos != p.attributes.end())
        need += (unsigned __int128)locate_accessor(model, pos->second, 3, what + " POSITION", input_bytes).accessor->count * 64;
      if (p.indices >= 0)
        need += (unsigned __int128)locate_accessor(model, p.indices, 1, what + " indices", input_bytes).accessor->count * 12;
    }
  if (need > (unsigned __int128)counts_limit(input_bytes, input_bytes))
    fail("its instances would build a mesh far larger than the file (a mesh named by many nodes): refused");
}

// Refuses a primitive meshsal does not read: Draco-compressed, points or lines, an unknown mode.
void check_primitive_mode(const tinygltf::Primitive& p, const std::string& what) {
  if (p.extensions.count("KHR_draco_mesh_compression"))
    fail(what + ": Draco-compressed (KHR_draco_mesh_compression), which meshsal does not read (decompress it first)");
  if (p.mode == TINYGLTF_MODE_POINTS || p.mode == TINYGLTF_MODE_LINE || p.mode == TINYGLTF_MODE_LINE_LOOP ||
      p.mode == TINYGLTF_MODE_LINE_STRIP)
    fail(what + ": " + (p.mode == TINYGLTF_MODE_POINTS ? "points" : "lines") +
         " (mode " + std::to_string(p.mode) + "): meshsal reads triangle primitives only");
  if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP && p.mode != TINYGLTF_MODE_TRIANGLE_FAN)
    fail(what + ": unknown mode " + std::to_string(p.mode));
}

// A primitive's corners (indices into its nv vertices): indexed or in vertex order.
std::vector<uint32_t> primitive_corners(const tinygltf::Model& model, const tinygltf::Primitive& p, size_t nv,
                                        const std::string& what, uint64_t input_bytes) {
  std::vector<uint32_t> corners;
  if (p.indices >= 0) {
    const tinygltf::Accessor* ia = size_t(p.indices) < model.accessors.size() ? &model.accessors[size_t(p.indices)] : nullptr;
    if (ia && ia->componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ia->componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ia->componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(what + ": indices must be unsigned integers");
    const std::vector<double> idx = read_accessor(model, p.indices, 1, what + " indices", input_bytes);
    corners.reserve(idx.size());
    for (double x : idx) {
      if (x >= double(nv)) fail(what + ": index " + std::to_string(uint64_t(x)) + " out of range (" + std::to_string(nv) + " vertices)");
      corners.push_back(uint32_t(x));
    }
  } else {
    corners.resize(nv);
    for (size_t v = 0; v < nv; ++v) corners[v] = uint32_t(v);
  }
  return corners;
}

// The triangles of a primitive's corners: strips and fans become triangles.
std::vector<std::array<uint32_t, 3>> corner_triangles(int mode, const std::vector<uint32_t>& corners, const std::string& what) {
  std::vector<std::array<uint32_t, 3>> tris;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (corners.size() % 3) fail(what + ": " + std::to_string(corners.size()) + " indices, not a multiple of 3");
    for (size_t i = 0; i + 2 < corners.size(); i += 3) tris.push_back({corners[i], corners[i + 1], corners[i + 2]});
  } else {
    for (size_t i = 0; i + 2 < corners.size(); ++i) {
      std::array<uint32_t, 3> t = mode == TINYGLTF_MODE_TRIANGLE_FAN ? std::array<uint32_t, 3>{corners[i + 1], corners[i + 2], corners[0]}
                                  : (i % 2 == 0)                      ? std::array<uint32_t, 3>{corners[i], corners[i + 1], corners[i + 2]}
                                                                      : std::array<uint32_t, 3>{corners[i + 1], corners[i], corners[i + 2]};
      // Strips join pieces with zero-area triangles that repeat a corner: dropped.
      if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) tris.push_back(t);
    }
  }
  return tris;
}

// The scene's instances as one Mesh, built one primitive at a time: positions in world
// coordinates, the channels' values, triangles and their materials.
class SceneMesh {
 public:
  SceneMesh(tinygltf::Model& model, uint64_t input_bytes, std::vector<Channel>& channels)
      : model_(model), input_bytes_(input_bytes), channels_(channels) {}

  void add_instance(size_t ii, const Instance& in) {
    const tinygltf::Mesh& gm = model_.meshes[size_t(in.mesh)];
    const Frame normal_frame = normal_matrix(in.world);
    const bool flip = determinant3(in.world) < 0;  // a mirroring transform reverses the winding
    for (size_t pi = 0; pi < gm.primitives.size(); ++pi) {
      const tinygltf::Primitive& p = gm.primitives[pi];
      const std::string what = "mesh " + std::to_string(in.mesh) + " primitive " + std::to_string(pi);
      check_primitive_mode(p, what);
      const auto [first, nv] = vertices(ii, in, p, normal_frame, what);
      const std::vector<std::array<uint32_t, 3>> tris = corner_triangles(p.mode, primitive_corners(model_, p, nv, what, input_bytes_), what);
      const uint32_t slot = material_slot(p, what);
      for (auto t : tris) {
        if (flip) std::swap(t[1], t[2]);
        for (uint32_t c : t) mesh_.triangles.push_back(uint32_t(first) + c);
        tri_material_.push_back(slot);
      }
    }
    worlds_.push_back(in.world);
  }

  // The mesh: its materials (and the assets they use), the channels as attributes, and
  // the scene's frame.
  Mesh finish(std::set<std::string>* skipped) {
    if (any_material_) {
      mesh_.triangle_material = std::move(tri_material_);
      mesh_.gltf_assets = carry_assets(model_, material_slot_, skipped);
    } else {
      mesh_.materials.clear();
    }
    for (Channel& c : channels_)
      for (VertexAttribute& a : c.attributes) mesh_.attributes.push_back(std::move(a));
    // One frame for the whole scene when every instance has the same one: a writer puts the
    // positions back in it (see Frame).
    if (worlds_[0] != identity_frame() &&
        std::all_of(worlds_.begin(), worlds_.end(), [&](const Frame& f) { return f == worlds_[0]; }))
      mesh_.frame.assign(worlds_[0].begin(), worlds_[0].end());
    return std::move(mesh_);
  }

 private:
  // A primitive's vertices (the first one's index, their count), read and appended unless
  // an earlier primitive of the instance named the same accessors (one per material, as
  // write_gltf and most exporters write them): then they are shared.
  std::pair<size_t, size_t> vertices(size_t ii, const Instance& in, const tinygltf::Primitive& p, const Frame& normal_frame,
                                     const std::string& what) {
    const auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) fail(what + ": no POSITION attribute");
    const auto range = vertex_ranges_.find({ii, p.attributes});
    if (range != vertex_ranges_.end()) return range->second;
    std::vector<double>& xyz = mesh_.source_positions;
    const std::vector<double> local = read_accessor(model_, pos->second, 3, what + " POSITION", input_bytes_);
    const size_t nv = local.size() / 3, first = xyz.size() / 3;
    if (first + nv > UINT32_MAX) fail("more than 2^32 - 1 vertices");
    for (size_t v = 0; v < nv; ++v) {
      double w[3];
      transform_point(in.world, &local[3 * v], w);
      xyz.insert(xyz.end(), w, w + 3);
    }
    for (Channel& c : channels_) read_channel(model_, p, c, nv, normal_frame, what, input_bytes_);
    vertex_ranges_[{ii, p.attributes}] = {first, nv};
    return {first, nv};
  }

  // The Mesh::materials slot of a primitive's material, added at its first use under a
  // unique name.
  uint32_t material_slot(const tinygltf::Primitive& p, const std::string& what) {
    if (p.material >= 0 && size_t(p.material) >= model_.materials.size())
      fail(what + ": material " + std::to_string(p.material) + " does not exist");
    if (p.material >= 0) any_material_ = true;
    const auto found = material_slot_.find(p.material);
    if (found != material_slot_.end()) return found->second;
    const uint32_t slot = uint32_t(mesh_.materials.size());
    material_slot_[p.material] = slot;
    std::string mname;
    if (p.material >= 0 && size_t(p.material) < model_.materials.size()) mname = model_.materials[size_t(p.material)].name;
    if (p.material >= 0 && mname.empty()) mname = "material_" + std::to_string(p.material);
    // Unique, as an OBJ's usemtl names must be to tell materials apart.
    if (std::find(mesh_.materials.begin(), mesh_.materials.end(), mname) != mesh_.materials.end())
      mname += "_" + std::to_string(p.material);
    mesh_.materials.push_back(mname);
    return slot;
  }

  tinygltf::Model& model_;
  const uint64_t input_bytes_;
  std::vector<Channel>& channels_;
  Mesh mesh_;
  std::map<int, uint32_t> material_slot_;  // glTF material index (-1: none) -> Mesh::materials
  std::vector<uint32_t> tri_material_;
  bool any_material_ = false;
  std::vector<Frame> worlds_;
  std::map<std::pair<size_t, std::map<std::string, int>>, std::pair<size_t, size_t>> vertex_ranges_;
};

}  // namespace

Mesh load_gltf_bytes(std::string_view bytes, const std::string& /*name: load_named prefixes it*/, bool binary, const std::string& folder,
                     uint64_t limit, bool attributes, std::vector<std::string>* unread, std::vector<std::string>* not_read) {
  // Not const: carry_assets takes the images' bytes over.
  tinygltf::Model model = parse_model(bytes, binary, folder, limit);
  const std::vector<Instance> instances = scene_instances(model);
  if (instances.empty()) fail("the scene holds no mesh");
  std::set<std::string> skipped;
  std::vector<Channel> channels;
  if (attributes) {
    channels = vertex_channels(model, instances, &skipped);
  } else {
    // What a read with attributes would have kept, in the names every reader uses.
    std::set<std::string> ignored;
    for (const Channel& c : vertex_channels(model, instances, &ignored))
      for (const VertexAttribute& a : c.attributes) note_not_read(not_read, a.name);
  }
  const uint64_t input_bytes = bytes.size() + [&] {
    uint64_t b = 0;
    for (const tinygltf::Buffer& buf : model.buffers) b += buf.data.size();
    return b;
  }();
  check_scene_size(model, instances, input_bytes);

  SceneMesh scene(model, input_bytes, channels);
  for (size_t ii = 0; ii < instances.size(); ++ii) scene.add_instance(ii, instances[ii]);
  Mesh mesh = scene.finish(&skipped);
  if (unread) unread->assign(skipped.begin(), skipped.end());
  localize_read_positions(mesh);
  // Primitives (and instances) meet at duplicated vertices: linked as seam twins, so the
  // saliency sees one surface while each vertex keeps its own attributes.
  link_position_twins(mesh);
  return mesh;
}

}  // namespace meshsal
