// glTF input within bounds: JSON nesting refused before any parser recurses into it, no
// allocation sized by a count before the file is known to back it, unknown required
// extensions refused by name, dangling material references dropped with a note (so that
// the output is valid glTF), and images that share a bufferView carried once.
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli/synthetic.h"
#include "cli_run.h"
#include "gltf_util.h"
#include "io/gltf_assets.h"
#include "io/json_nesting.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using namespace meshsal;
using meshsal_test::GltfBytes;
using meshsal_test::TempDir;

namespace {

// One triangle with positions (accessor 0, bufferView 0) and indices (accessor 1,
// bufferView 1) in a data: buffer; `top` is added to the top-level object, `attributes` to
// the primitive's attributes, `accessors` to the accessors, `views` to the bufferViews
// ("@EXTRA@" there: the offset of `extra_data`), `primitive` to the primitive.
std::string triangle(const std::string& top = "", const std::string& attributes = "", const std::string& accessors = "",
                     const std::string& views = "", const std::vector<uint8_t>& extra_data = {},
                     const std::string& primitive = "") {
  GltfBytes b;
  const size_t pos = b.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  const size_t idx = b.add(std::vector<uint32_t>{0, 1, 2});
  const size_t more = extra_data.empty() ? 0 : b.add(extra_data);
  std::string v = views;
  const std::string at = "@EXTRA@";
  if (const size_t k = v.find(at); k != std::string::npos) v.replace(k, at.size(), std::to_string(more));
  return "{\"asset\":{\"version\":\"2.0\"}" + top + ",\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
         "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0" + attributes + "}" + primitive + "}]}],"
         "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
         "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}" + accessors + "],"
         "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":" + std::to_string(pos) + ",\"byteLength\":36},"
         "{\"buffer\":0,\"byteOffset\":" + std::to_string(idx) + ",\"byteLength\":12}" + v + "],"
         "\"buffers\":[" + b.buffer_json() + "]}";
}

Mesh load_text(const std::string& json, const std::string& name = "t.gltf", bool attributes = false) {
  LoadOptions o;
  o.attributes = attributes;
  return load_mesh_bytes(json, name, o);
}

std::string nested_arrays(size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

}  // namespace

TEST_CASE("json nesting: counted without recursion, strings and escapes skipped", "[io][gltf]") {
  CHECK(json_nesting("1") == 0);
  CHECK(json_nesting("[[[]],{}]") == 3);
  CHECK(json_nesting("{\"a\":\"[[[{{{\"}") == 1);
  CHECK(json_nesting("{\"a\\\"[[\":[\"\\\\\",[]]}") == 3);  // an escaped quote, then an escaped backslash
  CHECK(json_nesting(nested_arrays(1000000)) == kMaxJsonNesting + 1);  // stops counting there
  CHECK(json_nesting(nested_arrays(1000), 5000) == 1000);
}

TEST_CASE("gltf limits: JSON nested deeper than the limit is refused before parsing, text and GLB", "[io][gltf]") {
  // The file's own structure nests 6 deep (meshes/primitives/attributes); extras under
  // asset start at depth 3, so k arrays there make the file's nesting 2 + k.
  const auto with_extras = [](size_t k) {
    std::string t = triangle();
    t.replace(t.find("\"2.0\"}"), 6, "\"2.0\",\"extras\":" + nested_arrays(k) + "}");
    return t;
  };
  CHECK(load_text(with_extras(kMaxJsonNesting - 2)).triangle_count() == 1);
  CHECK_THROWS_WITH(load_text(with_extras(kMaxJsonNesting - 1)), Catch::Contains("t.gltf: its JSON nests deeper than 64 levels"));
  // 20,000 deep in 40 KB overflowed tinygltf's stack (SIGSEGV) in every front end.
  CHECK_THROWS_WITH(load_text(with_extras(20000)), Catch::Contains("nests deeper than 64 levels"));
  CHECK_THROWS_WITH(load_text(meshsal_test::glb_file(with_extras(20000)), "t.glb"), Catch::Contains("t.glb: its JSON nests deeper"));
  // Through the command (and so batch and Python, which call the same loader).
  TempDir dir;
  const std::string deep = dir.write("deep.gltf", with_extras(200000));
  const meshsal_test::CliRun r = meshsal_test::run_cli("saliency " + meshsal_test::quoted(deep) + " -o " +
                                                       meshsal_test::quoted(dir.file("o.ply")), dir.path);
  CHECK(r.rc == 1);
  CHECK_THAT(r.err, Catch::Contains("nests deeper than 64 levels"));
}

TEST_CASE("gltf limits: a count is checked against the file before anything is allocated for it", "[io][gltf]") {
  // A sparse NORMAL with no base data declaring 10^8 elements (2.4 GB as doubles): refused
  // for not matching POSITION's count, before its zeros are allocated.
  GltfBytes extra;
  const std::string sparse_normal =
      ",{\"componentType\":5126,\"count\":100000000,\"type\":\"VEC3\",\"sparse\":{\"count\":1,"
      "\"indices\":{\"bufferView\":1,\"componentType\":5125},\"values\":{\"bufferView\":0}}}";
  CHECK_THROWS_WITH(load_text(triangle("", ",\"NORMAL\":2", sparse_normal), "t.gltf", true),
                    Catch::Contains("NORMAL: 100000000 elements where POSITION has 3"));
  // The same as POSITION itself: more zeros than the file could hold dense.
  std::string t = triangle("", "", sparse_normal);
  t.replace(t.find("\"POSITION\":0"), 12, "\"POSITION\":2");
  CHECK_THROWS_WITH(load_text(t), Catch::Contains("declares 100000000 elements with no bufferView, more than the file's"));
  // A count past 2^32 is named as what it is (not as "a mesh named by many nodes").
  std::string huge = triangle();
  const std::string vec3 = "\"count\":3,\"type\":\"VEC3\"";
  huge.replace(huge.find(vec3), vec3.size(), "\"count\":5000000000,\"type\":\"VEC3\"");
  CHECK_THROWS_WITH(load_text(huge), Catch::Contains("5000000000 elements run past the end of bufferView 0"));
  // A negative sparse byteOffset.
  const std::string negative =
      ",{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"sparse\":{\"count\":1,"
      "\"indices\":{\"bufferView\":1,\"componentType\":5125,\"byteOffset\":-4},\"values\":{\"bufferView\":0}}}";
  CHECK_THROWS_WITH(load_text(triangle("", ",\"NORMAL\":2", negative), "t.gltf", true),
                    Catch::Contains("negative sparse byteOffset"));
}

TEST_CASE("gltf limits: an unknown required extension is refused by name, known ones read", "[io][gltf]") {
  CHECK_THROWS_WITH(load_text(triangle(",\"extensionsUsed\":[\"EXT_mystery\"],\"extensionsRequired\":[\"EXT_mystery\"]")),
                    Catch::Contains("requires the extension 'EXT_mystery', which meshsal does not know"));
  // Used but not required: read (a reader may ignore it).
  CHECK(load_text(triangle(",\"extensionsUsed\":[\"EXT_mystery\"]")).triangle_count() == 1);
  CHECK(load_text(triangle(",\"extensionsUsed\":[\"KHR_texture_transform\"],\"extensionsRequired\":[\"KHR_texture_transform\"]"))
            .triangle_count() == 1);
}

TEST_CASE("gltf limits: dangling texture, image and sampler references are dropped with a note", "[io][gltf][validator]") {
  const std::string top =
      ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":5}},\"normalTexture\":{\"index\":0},"
      "\"extensions\":{\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1,\"clearcoatTexture\":{\"index\":9}}}}],"
      "\"textures\":[{\"source\":3,\"sampler\":2}],\"extensionsUsed\":[\"KHR_materials_clearcoat\"]";
  const LoadedMesh read = read_mesh_bytes(triangle(top, "", "", "", {}, ",\"material\":0"), "t.gltf");
  const Mesh& m = read.mesh;
  const LoadReport& report = read.report;
  REQUIRE(m.gltf_assets != nullptr);
  const GltfAssets& a = *m.gltf_assets;
  // Texture 0 lost its image, so it is gone and the material's normal map with it.
  CHECK(a.textures.empty());
  CHECK(a.materials[0].pbrMetallicRoughness.baseColorTexture.index == -1);
  CHECK(a.materials[0].normalTexture.index == -1);
  CHECK_FALSE(a.materials[0].extensions.at("KHR_materials_clearcoat").Has("clearcoatTexture"));
  CHECK(a.materials[0].extensions.at("KHR_materials_clearcoat").Has("clearcoatFactor"));
  const std::vector<std::string> expect = {
      "material 0's KHR_materials_clearcoat's clearcoatTexture names texture 9, which does not exist: dropped",
      "material 0's baseColorTexture names texture 5, which does not exist: dropped",
      "material 0's normalTexture names texture 0, which has no image left: dropped",
      "texture 0 names image 3, which does not exist: dropped",
      "texture 0 names sampler 2, which does not exist: dropped"};
  for (const std::string& e : expect) CHECK(std::find(report.unread.begin(), report.unread.end(), e) != report.unread.end());
  TempDir dir;
  write_gltf(dir.file("out.glb"), m);
  std::string validator;
  CHECK(meshsal_test::validate_gltf(dir.file("out.glb"), &validator) == 0);
  INFO(validator);
  CHECK(validator.find(": 0 errors") != std::string::npos);
}

TEST_CASE("gltf limits: images sharing one bufferView are carried once", "[io][gltf]") {
  // 2,000 images naming one 64 KB bufferView: one copy in memory and in the output (a 2 MB
  // file made 1 GB of copies).
  std::vector<uint8_t> png(65536, 7);
  const uint8_t magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::copy(magic, magic + 8, png.begin());
  std::string images = ",\"images\":[";
  for (int i = 0; i < 2000; ++i) images += std::string(i ? "," : "") + "{\"bufferView\":2,\"mimeType\":\"image/png\"}";
  images += "],\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],\"textures\":[{\"source\":1999}]";
  const Mesh m = load_text(triangle(images, "", "", ",{\"buffer\":0,\"byteOffset\":@EXTRA@,\"byteLength\":65536}", png, ",\"material\":0"));
  REQUIRE(m.gltf_assets != nullptr);
  CHECK(m.gltf_assets->images.size() == 2000);
  CHECK(m.gltf_assets->image_bytes.size() == 1);
  CHECK(m.gltf_assets->image_bytes[0] == png);
  TempDir dir;
  write_gltf(dir.file("out.glb"), m);
  CHECK(std::filesystem::file_size(dir.file("out.glb")) < 65536 + 200000);
  LoadOptions o;
  const Mesh back = load_mesh(dir.file("out.glb"), o);
  REQUIRE(back.gltf_assets != nullptr);
  CHECK(back.gltf_assets->image_bytes.size() == 1);
  CHECK(back.gltf_assets->image_source[1999] == 0);
}

TEST_CASE("gltf limits: a deeply nested glTF fails alone in every front end", "[io][gltf][cli]") {
  // 20,000 levels of extras in 40 KB: batch logged nothing and died on every resume; under
  // --memory-limit the temporary folder stayed. Now the model fails with its message.
  TempDir dir;
  std::string deep = triangle();
  deep.replace(deep.find("\"2.0\"}"), 6, "\"2.0\",\"extras\":" + nested_arrays(20000) + "}");
  std::filesystem::create_directories(dir.file("in"));
  dir.write("in/deep.gltf", deep);
  write_mesh(dir.file("in/good.ply"), make_bumpy_sphere(1));
  const std::string batch = "batch " + meshsal_test::quoted(dir.file("in")) + " -o " + meshsal_test::quoted(dir.file("out")) +
                            " --backend cpu -q";
  for (int run = 0; run < 2; ++run) {  // the second run resumes: the good model skipped, the bad one failing again
    const meshsal_test::CliRun r = meshsal_test::run_cli(batch, dir.path);
    INFO(r.err);
    CHECK(r.rc == 1);
    const std::string log = meshsal_test::read_file(dir.file("out/batch.jsonl"));
    CHECK(log.find("its JSON nests deeper than 64 levels") != std::string::npos);
    CHECK(log.find(run == 0 ? "\"status\": \"done\"" : "\"status\": \"skipped\"") != std::string::npos);
  }
  CHECK(std::filesystem::exists(dir.file("out/good_saliency.ply")));
  // Out of core: the error, and no temporary folder left behind.
  std::filesystem::create_directories(dir.file("tmp"));
  const meshsal_test::CliRun ooc = meshsal_test::run_cli(
      "saliency " + meshsal_test::quoted(dir.file("in/deep.gltf")) + " -o " + meshsal_test::quoted(dir.file("o.ply")) +
          " --memory-limit 100M --temp-dir " + meshsal_test::quoted(dir.file("tmp")),
      dir.path);
  CHECK(ooc.rc == 1);
  CHECK(ooc.err.find("nests deeper than 64 levels") != std::string::npos);
  CHECK(std::filesystem::is_empty(dir.file("tmp")));
}
