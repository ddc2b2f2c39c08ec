// glTF 2.0 input and output: node transforms, strips and fans, primitives welded into one
// surface, sparse and quantised accessors, every hostile field refused with a message, the
// round trip (the saliency of a mesh equals that of its GLB), and every glTF we write
// clean under the Khronos validator.
#include <sys/stat.h>
#include <sys/wait.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli/synthetic.h"
#include "gltf_util.h"
#include "io/gltf_assets.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"
#include "test_util.h"

using namespace meshsal;
using meshsal_test::GltfBytes;
using meshsal_test::TempDir;

namespace {

// One triangle (0,0,0) (1,0,0) (0,1,0) as a .gltf whose node and primitive JSON the test
// gives; accessor 0: positions, accessor 1: indices 0 1 2.
std::string one_triangle(const std::string& nodes_and_scene, const std::string& primitive_extra = "",
                         const std::string& extra_top = "") {
  GltfBytes b;
  const size_t pos = b.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  const size_t idx = b.add(std::vector<uint32_t>{0, 1, 2});
  return "{\"asset\":{\"version\":\"2.0\"}," + nodes_and_scene + extra_top +
         ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1" + primitive_extra + "}]}]," +
         "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]}," +
         "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}]," +
         "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":" + std::to_string(pos) + ",\"byteLength\":36}," +
         "{\"buffer\":0,\"byteOffset\":" + std::to_string(idx) + ",\"byteLength\":12}]," +
         "\"buffers\":[" + b.buffer_json() + "]}";
}

Mesh load_text(const std::string& json, const std::string& name = "t.gltf", bool attributes = false) {
  LoadOptions o;
  o.attributes = attributes;
  return load_mesh_bytes(json, name, o);
}

std::vector<double> world(const Mesh& m) { return model_positions(m); }

// `s` with its first `from` replaced by `to` (which must be there).
std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

SaliencyOptions cpu_exact() {
  SaliencyOptions o;
  o.backend = Backend::Cpu;
  return o;
}

}  // namespace

TEST_CASE("gltf: node transforms (matrix, TRS, hierarchy) are applied in double", "[io][gltf]") {
  // Translation, then a child with a 90-degree turn about z and scale 2.
  const std::string nodes =
      "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"translation\":[10,20,30],\"children\":[1]},"
      "{\"mesh\":0,\"rotation\":[0,0,0.7071067811865476,0.7071067811865476],\"scale\":[2,2,2]}]";
  const Mesh m = load_text(one_triangle(nodes));
  const std::vector<double> p = world(m);
  REQUIRE(p.size() == 9);
  const double want[9] = {10, 20, 30, 10, 22, 30, 8, 20, 30};  // (1,0,0) -> (0,2,0); (0,1,0) -> (-2,0,0)
  for (int i = 0; i < 9; ++i) CHECK(p[size_t(i)] == Approx(want[i]).margin(1e-12));
  // The one instance's transform is kept, for writing the positions back in it.
  REQUIRE(m.frame.size() == 16);
  CHECK(m.frame[12] == Approx(10));
  CHECK(m.frame[1] == Approx(2).margin(1e-12));  // column 0 = R * S * x = (0, 2, 0)

  // A matrix (column-major) mirroring x: the winding turns so the normal stays outward.
  const Mesh mirrored =
      load_text(one_triangle("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"matrix\":[-1,0,0,0,0,1,0,0,0,0,1,0,5,0,0,1]}]"));
  const std::vector<double> q = world(mirrored);
  CHECK(q[3] == Approx(4));  // (1,0,0) -> (4,0,0)
  CHECK(mirrored.triangles == std::vector<uint32_t>{0, 2, 1});

  // Two instances of the mesh: six vertices, two triangles, no shared frame.
  const Mesh twice = load_text(one_triangle(
      "\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0},{\"mesh\":0,\"translation\":[0,0,1]}]"));
  CHECK(twice.vertex_count() == 6);
  CHECK(twice.triangle_count() == 2);
  CHECK(twice.frame.empty());
  CHECK(world(twice)[17] == Approx(1));
}

TEST_CASE("gltf: strips and fans become triangles, points and lines are refused", "[io][gltf]") {
  GltfBytes b;
  const size_t pos = b.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0});
  auto file = [&](int mode) {
    return "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"mode\":" + std::to_string(mode) + "}]}],"
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":5,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[2,1,0]}],"
           "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":" + std::to_string(pos) + ",\"byteLength\":60}],"
           "\"buffers\":[" + b.buffer_json() + "]}";
  };
  // Strip 0 1 2 3 4: (0 1 2) (2 1 3) (2 3 4), every other one turned to keep the winding.
  CHECK(load_text(file(5)).triangles == std::vector<uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 4});
  // Fan: (1 2 0) (2 3 0) (3 4 0).
  CHECK(load_text(file(6)).triangles == std::vector<uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0});
  CHECK_THROWS_WITH(load_text(file(0)), Catch::Contains("points (mode 0): meshsal reads triangle primitives only"));
  CHECK_THROWS_WITH(load_text(file(1)), Catch::Contains("lines (mode 1)"));
  CHECK_THROWS_WITH(load_text(file(3)), Catch::Contains("lines (mode 3)"));
  CHECK_THROWS_WITH(load_text(file(4)), Catch::Contains("not a multiple of 3"));
}

TEST_CASE("gltf: sparse accessors and quantised positions are read", "[io][gltf]") {
  GltfBytes b;
  const size_t base = b.add(std::vector<uint16_t>{0, 0, 0, 65535, 0, 0, 0, 65535, 0, 0, 0});  // 3 x VEC3 ushort, + pad
  const size_t sidx = b.add(std::vector<uint8_t>{2, 0, 0, 0});
  const size_t sval = b.add(std::vector<uint16_t>{0, 32768, 0, 0});
  const std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_mesh_quantization\"],"
      "\"extensionsRequired\":[\"KHR_mesh_quantization\"],\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5123,\"normalized\":true,\"count\":3,\"type\":\"VEC3\","
      "\"min\":[0,0,0],\"max\":[1,1,0],\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5121},"
      "\"values\":{\"bufferView\":2}}}],"
      "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":" + std::to_string(base) + ",\"byteLength\":18},"
      "{\"buffer\":0,\"byteOffset\":" + std::to_string(sidx) + ",\"byteLength\":1},"
      "{\"buffer\":0,\"byteOffset\":" + std::to_string(sval) + ",\"byteLength\":6}],"
      "\"buffers\":[" + b.buffer_json() + "]}";
  const std::vector<double> p = world(load_text(json));
  REQUIRE(p.size() == 9);
  CHECK(p[3] == Approx(1.0));                 // 65535 normalised
  CHECK(p[6] == Approx(0.0));                 // vertex 2 replaced by the sparse value (0, 0.5, 0)
  CHECK(p[7] == Approx(32768 / 65535.0));
}

TEST_CASE("gltf: hostile files give a message, never a read out of bounds", "[io][gltf]") {
  const std::string scene = "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}]";
  std::string t = one_triangle(scene);
  // An index past the vertices.
  GltfBytes b;
  b.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  b.add(std::vector<uint32_t>{0, 1, 7});
  std::string bad_index = t;
  bad_index.replace(bad_index.find("\"buffers\":["), std::string::npos, "\"buffers\":[" + b.buffer_json() + "]}");
  CHECK_THROWS_WITH(load_text(bad_index), Catch::Contains("index 7 out of range (3 vertices)"));
  // An accessor longer than its bufferView.
  CHECK_THROWS_WITH(load_text(replaced(t, "\"count\":3,\"type\":\"VEC3\"", "\"count\":4,\"type\":\"VEC3\"")),
                    Catch::Contains("run past the end of bufferView 0"));
  // A bufferView past its buffer.
  CHECK_THROWS_WITH(load_text(replaced(t, "\"byteLength\":36", "\"byteLength\":3600")), Catch::Contains("t.gltf: "));
  // A node cycle and a node reached twice.
  CHECK_THROWS_WITH(load_text(one_triangle("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}]")),
                    Catch::Contains("reached twice"));
  // Compression and instancing extensions are named.
  CHECK_THROWS_WITH(load_text(one_triangle(scene, ",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":0,\"attributes\":{\"POSITION\":0}}}")),
                    Catch::Contains("Draco-compressed (KHR_draco_mesh_compression)"));
  CHECK_THROWS_WITH(load_text(one_triangle(scene, "", ",\"extensionsUsed\":[\"EXT_meshopt_compression\"],\"extensionsRequired\":[\"EXT_meshopt_compression\"]")),
                    Catch::Contains("requires the extension EXT_meshopt_compression"));
  // A mesh named by many nodes cannot build a mesh far larger than the file: 1,000
  // instances of 100,000 vertices from a 1.6 MB file.
  {
    GltfBytes big;
    big.add(std::vector<float>(300000, 0.0f));
    big.add(std::vector<uint32_t>{0, 1, 2});
    std::string many = "\"scenes\":[{\"nodes\":[";
    for (int i = 0; i < 1000; ++i) many += (i ? "," : "") + std::to_string(i);
    many += "]}],\"nodes\":[";
    for (int i = 0; i < 1000; ++i) many += std::string(i ? "," : "") + "{\"mesh\":0}";
    many += "]";
    std::string json = one_triangle(many);
    json = replaced(json, "\"count\":3,\"type\":\"VEC3\"", "\"count\":100000,\"type\":\"VEC3\"");
    json = replaced(json, "\"byteLength\":36}", "\"byteLength\":1200000}");
    json = replaced(json, "\"byteOffset\":36,\"byteLength\":12", "\"byteOffset\":1200000,\"byteLength\":12");
    json.replace(json.find("\"buffers\":["), std::string::npos, "\"buffers\":[" + big.buffer_json() + "]}");
    CHECK_THROWS_WITH(load_text(json), Catch::Contains("far larger than the file"));
  }
  // From memory an external buffer cannot be read.
  const size_t uri = t.find("data:application");
  REQUIRE(uri != std::string::npos);
  std::string external = t;
  external.replace(uri, t.find('"', uri) - uri, "mesh.bin");
  CHECK_THROWS_WITH(load_text(external), Catch::Contains("external file"));
  // Not JSON at all; a GLB with a bad header.
  CHECK_THROWS_WITH(load_text("{ not json"), Catch::Contains("t.gltf: not a valid glTF file"));
  CHECK_THROWS_WITH(load_text(std::string("glTF\2\0\0\0\20\0\0\0", 12), "t.glb"), Catch::Contains("t.glb: not a valid glTF file"));
}

TEST_CASE("gltf: a .gltf reads its .bin beside it, and never waits on a FIFO", "[io][gltf]") {
  TempDir dir;
  GltfBytes b;
  b.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  b.add(std::vector<uint32_t>{0, 1, 2});
  {
    std::ofstream(dir.file("mesh.bin"), std::ios::binary).write(reinterpret_cast<const char*>(b.data.data()), std::streamsize(b.data.size()));
  }
  std::string json = one_triangle("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}]");
  const size_t at = json.find("\"buffers\":[");
  json.replace(at, std::string::npos, "\"buffers\":[{\"byteLength\":" + std::to_string(b.data.size()) + ",\"uri\":\"mesh.bin\"}]}");
  const std::string path = dir.write("scene.gltf", json);
  CHECK(load_mesh(path).triangle_count() == 1);
  // The same buffer as a named pipe: refused at once (a plain read would block forever).
  std::remove(dir.file("mesh.bin").c_str());
  REQUIRE(::mkfifo(dir.file("mesh.bin").c_str(), 0600) == 0);
  CHECK_THROWS_WITH(load_mesh(path), Catch::Contains("scene.gltf: 'mesh.bin': not a regular file"));
}

TEST_CASE("gltf: primitives meeting at duplicated vertices are one surface for saliency", "[io][gltf]") {
  // A bumpy sphere cut into two primitives by a plane, each with its own copy of the
  // vertices along the cut: its saliency equals the whole mesh's at every vertex.
  // The whole mesh from the floats the file will hold, so both have the same origin.
  const Mesh base = make_bumpy_sphere(3);
  const std::vector<float> floats = meshsal_test::world_floats(base);
  const Mesh whole = make_mesh(floats.data(), base.vertex_count(), base.triangles.data(), base.triangles.size());
  std::vector<uint32_t> upper, lower;
  for (size_t t = 0; t < whole.triangle_count(); ++t) {
    float z = 0;
    for (int k = 0; k < 3; ++k) z += whole.positions[3 * whole.triangles[3 * t + size_t(k)] + 2];
    (z > 0 ? upper : lower).insert((z > 0 ? upper : lower).end(), &whole.triangles[3 * t], &whole.triangles[3 * t] + 3);
  }
  GltfBytes b;
  std::string accessors, views, prims;
  int acc = 0;
  for (const auto* part : {&upper, &lower}) {
    std::vector<float> pos;
    std::vector<uint32_t> idx, map(whole.vertex_count(), UINT32_MAX);
    for (uint32_t v : *part) {
      if (map[v] == UINT32_MAX) {
        map[v] = uint32_t(pos.size() / 3);
        pos.insert(pos.end(), &floats[3 * v], &floats[3 * v] + 3);
      }
      idx.push_back(map[v]);
    }
    const size_t p = b.add(pos), i = b.add(idx);
    const std::string v0 = std::to_string(acc), v1 = std::to_string(acc + 1);
    views += std::string(acc ? "," : "") + "{\"buffer\":0,\"byteOffset\":" + std::to_string(p) + ",\"byteLength\":" + std::to_string(pos.size() * 4) + "}," +
             "{\"buffer\":0,\"byteOffset\":" + std::to_string(i) + ",\"byteLength\":" + std::to_string(idx.size() * 4) + "}";
    accessors += std::string(acc ? "," : "") + "{\"bufferView\":" + v0 + ",\"componentType\":5126,\"count\":" + std::to_string(pos.size() / 3) +
                 ",\"type\":\"VEC3\"},{\"bufferView\":" + v1 + ",\"componentType\":5125,\"count\":" + std::to_string(idx.size()) + ",\"type\":\"SCALAR\"}";
    prims += std::string(acc ? "," : "") + "{\"attributes\":{\"POSITION\":" + v0 + "},\"indices\":" + v1 + "}";
    acc += 2;
  }
  const std::string json = "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[" +
                           prims + "]}],\"accessors\":[" + accessors + "],\"bufferViews\":[" + views + "],\"buffers\":[" + b.buffer_json() + "]}";
  const Mesh split = load_text(json);
  REQUIRE(split.vertex_count() > whole.vertex_count());  // the cut's vertices twice
  REQUIRE(split.position_vertex.size() == split.vertex_count());
  const SaliencyResult a = compute_saliency(whole, cpu_exact());
  const SaliencyResult s = compute_saliency(split, cpu_exact());
  // Each split vertex against the whole mesh's vertex at its position.
  const std::vector<double> pw = world(whole), ps = world(split);
  size_t matched = 0;
  for (size_t v = 0; v < split.vertex_count(); ++v)
    for (size_t w = 0; w < whole.vertex_count(); ++w)
      if (pw[3 * w] == ps[3 * v] && pw[3 * w + 1] == ps[3 * v + 1] && pw[3 * w + 2] == ps[3 * v + 2]) {
        CHECK(s.saliency[v] == Approx(a.saliency[w]).margin(1e-9));
        ++matched;
        break;
      }
  CHECK(matched == split.vertex_count());
}

TEST_CASE("gltf: OBJ -> GLB -> saliency equals the OBJ's at every vertex, transform undone", "[io][gltf]") {
  TempDir dir;
  const Mesh obj_mesh = make_bumpy_sphere(3);
  write_obj(dir.file("m.obj"), obj_mesh);
  const Mesh obj = load_mesh(dir.file("m.obj"));
  const SaliencyResult want = compute_saliency(obj, cpu_exact());
  // Straight through: the model's coordinates as floats under no node transform, as a
  // float PLY holds them (a reader that ignores nodes sees the model where the PLY puts it):
  // the positions and saliency of the PLY route bit for bit, the OBJ's to float rounding.
  write_gltf(dir.file("m.glb"), obj, want.saliency);
  write_ply(dir.file("m.ply"), obj, {});
  const Mesh glb = load_mesh(dir.file("m.glb")), ply = load_mesh(dir.file("m.ply"));
  REQUIRE(glb.vertex_count() == obj.vertex_count());
  CHECK(glb.frame.empty());
  CHECK(glb.positions == ply.positions);
  const std::vector<double> gw = world(glb), ow0 = world(obj);
  for (size_t i = 0; i < gw.size(); ++i) CHECK(gw[i] == Approx(ow0[i]).margin(1e-7));
  CHECK(glb.triangles == obj.triangles);
  const std::vector<double> via_glb = compute_saliency(glb, cpu_exact()).saliency;
  CHECK(via_glb == compute_saliency(ply, cpu_exact()).saliency);
  const double s_max = *std::max_element(want.saliency.begin(), want.saliency.end());
  for (size_t v = 0; v < via_glb.size(); ++v) CHECK(via_glb[v] == Approx(want.saliency[v]).margin(1e-5 * s_max));
  // Under a node turned a quarter, scaled by 2 and moved (a file made elsewhere; a transform
  // exact in binary, so the saliency can be compared closely: it is invariant to
  // similarity transforms), and undoing the transform gives the positions back.
  Mesh framed = obj;
  const double c = 0, s = 1;
  framed.frame = {2 * c, 2 * s, 0, 0, -2 * s, 2 * c, 0, 0, 0, 0, 2, 0, 100, -50, 7, 1};
  // write_gltf writes the positions in the frame (they are world coordinates): make them so.
  std::vector<double> w = world(obj);
  for (size_t v = 0; v < obj.vertex_count(); ++v) {
    const double x = w[3 * v], y = w[3 * v + 1], z = w[3 * v + 2];
    w[3 * v] = 2 * c * x - 2 * s * y + 100, w[3 * v + 1] = 2 * s * x + 2 * c * y - 50, w[3 * v + 2] = 2 * z + 7;
  }
  set_model_positions(framed, w.data(), obj.vertex_count());
  write_gltf(dir.file("framed.glb"), framed);
  const Mesh back = load_mesh(dir.file("framed.glb"));
  REQUIRE(back.frame.size() == 16);
  for (int k = 0; k < 16; ++k) CHECK(back.frame[size_t(k)] == Approx(framed.frame[size_t(k)]).margin(1e-12));
  const std::vector<double> bw = world(back), ow = world(obj);
  for (size_t v = 0; v < obj.vertex_count(); ++v) {
    const double x = bw[3 * v] - 100, y = bw[3 * v + 1] + 50, z = bw[3 * v + 2] - 7;
    CHECK((c * x + s * y) / 2 == Approx(ow[3 * v]).margin(1e-5));
    CHECK((-s * x + c * y) / 2 == Approx(ow[3 * v + 1]).margin(1e-5));
    CHECK(z / 2 == Approx(ow[3 * v + 2]).margin(1e-5));
  }
  const SaliencyResult got = compute_saliency(back, cpu_exact());
  double top = 0, worst = 0;
  for (size_t v = 0; v < obj.vertex_count(); ++v)
    top = std::max(top, want.saliency[v]), worst = std::max(worst, std::abs(got.saliency[v] - want.saliency[v]));
  // The positions went through float in the node's frame (one rounding, 6e-7 of the top
  // measured): far below what the saliency's own cutoffs make of a float step.
  CHECK(worst <= 1e-5 * top);
}

TEST_CASE("gltf: what we write keeps attributes, materials and survey coordinates", "[io][gltf]") {
  TempDir dir;
  // An OBJ with UVs, normals and two materials, far from the origin.
  std::string obj = "mtllib m.mtl\n";
  obj += "v 500000.25 4000000.5 10\nv 500001.25 4000000.5 10\nv 500000.25 4000001.5 10\nv 500001.25 4000001.5 10.5\n";
  obj += "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvn 0 0 1\n";
  obj += "usemtl skin\nf 1/1/1 2/2/1 3/3/1\nusemtl eyes\nf 2/2/1 4/4/1 3/3/1\n";
  LoadOptions o;
  o.attributes = true;
  const Mesh m = load_mesh_bytes(obj, "m.obj", o);
  std::vector<double> sal{0.1, 0.2, 0.3, 0.4};
  write_gltf(dir.file("m.glb"), m, sal);
  const Mesh back = load_mesh(dir.file("m.glb"), o);
  CHECK(world(back) == world(m));  // to the bit: the node carries the origin
  CHECK(back.materials == std::vector<std::string>{"skin", "eyes"});
  CHECK(back.triangle_material == std::vector<uint32_t>{0, 1});
  auto attr = [](const Mesh& mesh, const char* name) -> std::vector<float> {
    for (const VertexAttribute& a : mesh.attributes)
      if (a.name == name) return a.values;
    return {};
  };
  CHECK(attr(back, "u") == attr(m, "u"));
  CHECK(attr(back, "v") == attr(m, "v"));
  CHECK(attr(back, "nz") == std::vector<float>{1, 1, 1, 1});
  // COLOR_0 carries the saliency colours: the top vertex dark red, the lowest blue.
  const std::vector<float> red = attr(back, "red"), blue = attr(back, "blue");
  REQUIRE(red.size() == 4);
  CHECK(red[3] > 100);
  CHECK(blue[0] > red[0]);
  // _SALIENCY comes back as the saliency attribute (kSaliencyAttribute), nothing unread.
  CHECK(read_mesh(dir.file("m.glb"), o).report.unread.empty());
  const std::vector<float> s = attr(back, kSaliencyAttribute);
  CHECK(s == std::vector<float>{0.1f, 0.2f, 0.3f, 0.4f});
  // These coordinates are floats: written as they are, under no node transform. Where
  // floats would move them (a tenth of a millimetre at 500 km), a translation node keeps them.
  CHECK(back.frame.empty());
  Mesh survey = m;
  std::vector<double> xyz = world(m);
  xyz[0] += 0.0001;
  set_model_positions(survey, xyz.data(), m.vertex_count());
  REQUIRE(positions_need_double(survey));
  write_gltf(dir.file("survey.glb"), survey);
  const std::vector<double> survey_back = world(load_mesh(dir.file("survey.glb"), o));
  for (size_t i = 0; i < xyz.size(); ++i) CHECK(survey_back[i] == Approx(xyz[i]).margin(1e-6));
}

TEST_CASE("gltf: every file we write passes the Khronos glTF-Validator", "[io][gltf][validator]") {
  TempDir dir;
  const Mesh sphere = make_bumpy_sphere(2);
  const SaliencyResult r = compute_saliency(sphere, cpu_exact());
  write_gltf(dir.file("s.glb"), sphere, r.saliency);
  write_gltf(dir.file("s.gltf"), sphere, r.saliency);
  // With attributes and materials, and a LOD chain.
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.5\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvn 0 0 1\nvn 0 0 0\n"
                    "usemtl a\nf 1/1/1 2/2/1 3/3/1\nusemtl b\nf 2/2/2 4/4/1 3/3/1\n";
  LoadOptions o;
  o.attributes = true;
  const Mesh m = load_mesh_bytes(obj, "m.obj", o);
  write_gltf(dir.file("m.glb"), m);
  std::vector<GltfLevel> levels(2);
  levels[0].mesh = &sphere;
  levels[0].saliency = &r.saliency;
  levels[1].mesh = &sphere;
  write_gltf(dir.file("lod.glb"), levels);
  for (const char* f : {"s.glb", "s.gltf", "m.glb", "lod.glb"}) {
    std::string report;
    const int rc = meshsal_test::validate_gltf(dir.file(f), &report);
    INFO(report);
    CHECK(rc == 0);
    CHECK(report.find(": 0 errors") != std::string::npos);
  }
}

TEST_CASE("gltf: a textured material is carried to the output unchanged", "[io][gltf][validator]") {
  TempDir dir;
  // A 4x4 PNG texture, a material using it, a triangle with UVs.
  write_png(dir.file("t.png"), Image(4, 4, 200, 30, 30));
  std::ifstream png_in(dir.file("t.png"), std::ios::binary);
  const std::vector<uint8_t> png((std::istreambuf_iterator<char>(png_in)), std::istreambuf_iterator<char>());
  GltfBytes b;
  const size_t pos = b.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  const size_t uv = b.add(std::vector<float>{0, 0, 1, 0, 0, 1});
  const size_t img = b.add(png);
  const std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},\"material\":0}]}],"
      "\"materials\":[{\"name\":\"painted\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},\"metallicFactor\":0.25}}],"
      "\"textures\":[{\"source\":0,\"sampler\":0}],\"samplers\":[{\"magFilter\":9728,\"wrapS\":33071}],"
      "\"images\":[{\"bufferView\":2,\"mimeType\":\"image/png\",\"name\":\"paint\"}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
      "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}],"
      "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":" + std::to_string(pos) + ",\"byteLength\":36},"
      "{\"buffer\":0,\"byteOffset\":" + std::to_string(uv) + ",\"byteLength\":24},"
      "{\"buffer\":0,\"byteOffset\":" + std::to_string(img) + ",\"byteLength\":" + std::to_string(png.size()) + "}],"
      "\"buffers\":[" + b.buffer_json() + "]}";
  LoadOptions o;
  o.attributes = true;
  const Mesh m = load_text(json, "t.gltf", true);
  REQUIRE(m.gltf_assets != nullptr);
  write_gltf(dir.file("out.glb"), m);
  const Mesh back = load_mesh(dir.file("out.glb"), o);
  REQUIRE(back.gltf_assets != nullptr);
  const GltfAssets& a = *back.gltf_assets;
  REQUIRE(a.images.size() == 1);
  REQUIRE(a.image_source.size() == 1);
  REQUIRE(a.image_source[0] == 0);
  CHECK(a.image_bytes[0] == png);  // the texture's bytes, as read
  CHECK(a.images[0].mimeType == "image/png");
  CHECK(a.images[0].name == "paint");
  REQUIRE(a.materials.size() == 1);
  CHECK(a.materials[0].name == "painted");
  CHECK(a.materials[0].pbrMetallicRoughness.baseColorTexture.index == 0);
  CHECK(a.materials[0].pbrMetallicRoughness.metallicFactor == 0.25);
  REQUIRE(a.samplers.size() == 1);
  CHECK(a.samplers[0].magFilter == 9728);
  CHECK(a.samplers[0].wrapS == 33071);
  CHECK(back.materials == std::vector<std::string>{"painted"});
  std::string report;
  CHECK(meshsal_test::validate_gltf(dir.file("out.glb"), &report) == 0);
  INFO(report);
  CHECK(report.find(": 0 errors") != std::string::npos);
}

TEST_CASE("gltf: files from gltfpack, quantised read and meshopt-compressed refused by name", "[io][gltf]") {
  // tests/data: bunny_3k simplified to 698 faces, written as GLB by meshsal, then through
  // Debian's gltfpack 0.18: default settings (KHR_mesh_quantization: 16-bit positions,
  // the scale and offset in the node) and -cc (EXT_meshopt_compression).
  const std::string data = std::string(MESHSAL_SOURCE_DIR) + "/tests/data/";
  const Mesh q = load_mesh(data + "bunny_quantized.glb");
  CHECK(q.vertex_count() == 351);
  CHECK(q.triangle_count() == 698);
  // The node's dequantising transform applied: the bunny's size (eps = 0.003 diagonal as
  // meshsal computed it for the unquantised GLB: 7.51422909e-4).
  SaliencyOptions o = cpu_exact();
  const SaliencyResult r = compute_saliency(q, o);
  CHECK(r.eps == Approx(7.51422909e-4).epsilon(1e-4));
  CHECK_THROWS_WITH(load_mesh(data + "bunny_meshopt.glb"),
                    Catch::Contains("bunny_meshopt.glb: uses the extension EXT_meshopt_compression, which meshsal does "
                                    "not read (decompress it first, e.g. with gltfpack -noq)"));
}
