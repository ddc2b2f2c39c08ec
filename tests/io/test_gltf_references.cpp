// Files that a model names (io/model_reference.h): a glTF's buffer and image URIs and an
// OBJ's mtllib stay in the model's folder or below, links resolved; a refusal names the
// reference and the rule, never the size of what it would have read; one budget covers
// all of a model's external bytes.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_run.h"
#include "gltf_util.h"
#include "io/model_reference.h"
#include "meshsal/meshsal.h"
#include "test_io_util.h"

using namespace meshsal;
using meshsal_test::GltfBytes;
using meshsal_test::TempDir;

namespace {

// One triangle's positions and indices, as an external buffer's bytes.
std::vector<uint8_t> triangle_bytes() {
  GltfBytes b;
  b.add(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  b.add(std::vector<uint32_t>{0, 1, 2});
  return b.data;
}

// A glTF whose buffer is `buffer_uri` (48 bytes: triangle_bytes()) and, when given, whose
// one material's texture is the image `image_uri`.
std::string triangle_gltf(const std::string& buffer_uri, const std::string& image_uri = "") {
  std::string material;
  if (!image_uri.empty())
    material = ",\"material\":0}]}],\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
               "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"" + image_uri + "\"}]";
  else
    material = "}]}]";
  return "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
         "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1" + material + ","
         "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
         "{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}],"
         "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":12}],"
         "\"buffers\":[{\"byteLength\":48,\"uri\":\"" + buffer_uri + "\"}]}";
}

std::string bytes_of(const std::vector<uint8_t>& v) { return std::string(v.begin(), v.end()); }

// A folder `model/` (the model's) inside a folder that also holds files the model must not
// reach: secret.bin (a valid buffer, so that only the rule can refuse it) and secret.png.
struct Layout {
  TempDir root;
  std::string model, secret;
  Layout() {
    model = root.file("model");
    std::filesystem::create_directories(model + "/sub");
    secret = root.write("secret.bin", bytes_of(triangle_bytes()));
    root.write("secret.png", std::string("\x89PNG\r\n\x1a\n", 8) + std::string(1571, 'x'));
    root.write("model/mesh.bin", bytes_of(triangle_bytes()));
    root.write("model/sub/mesh.bin", bytes_of(triangle_bytes()));
    root.write("model/tex.png", std::string("\x89PNG\r\n\x1a\n", 8) + std::string(20, 'p'));
  }
  std::string in_model(const std::string& name, const std::string& text) const { return root.write("model/" + name, text); }
};

std::string load_error(const std::string& path) {
  try {
    load_mesh(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("model references: the rule by the text of the name", "[io][gltf][references]") {
  CHECK(reference_text_problem("mesh.bin", true).empty());
  CHECK(reference_text_problem("sub/../mesh.bin", true).empty());
  CHECK(reference_text_problem("./a:b.bin", true).empty());  // RFC 3986's way to write a colon
  CHECK(reference_text_problem("a:b.bin", false).empty());   // an OBJ name is a plain path
  CHECK_THAT(reference_text_problem("../mesh.bin", true), Catch::Contains("leaves the model's folder"));
  CHECK_THAT(reference_text_problem("sub/../../mesh.bin", true), Catch::Contains("leaves the model's folder"));
  CHECK_THAT(reference_text_problem("/etc/hostname", true), Catch::Contains("an absolute path"));
  CHECK_THAT(reference_text_problem("file:///etc/hostname", true), Catch::Contains("the scheme 'file:'"));
  CHECK_THAT(reference_text_problem("https://example.com/x.bin", true), Catch::Contains("the scheme 'https:'"));
  CHECK_THAT(reference_text_problem("", true), Catch::Contains("empty"));
  CHECK_THAT(reference_text_problem(std::string("a\0b", 3), true), Catch::Contains("NUL"));
  CHECK_THAT(reference_text_problem("sub/..", true), Catch::Contains("folder itself"));
}

TEST_CASE("gltf references: buffers and images outside the model's folder are refused, named, with the rule", "[io][gltf][references]") {
  Layout l;
  // Allowed: beside the model, below it, '..' that stays inside, a link that stays inside.
  CHECK(load_mesh(l.in_model("plain.gltf", triangle_gltf("mesh.bin", "tex.png"))).triangle_count() == 1);
  CHECK(load_mesh(l.in_model("below.gltf", triangle_gltf("sub/mesh.bin"))).triangle_count() == 1);
  CHECK(load_mesh(l.in_model("dotdot.gltf", triangle_gltf("sub/../mesh.bin"))).triangle_count() == 1);
  REQUIRE(::symlink("sub/mesh.bin", (l.model + "/inside_link.bin").c_str()) == 0);
  CHECK(load_mesh(l.in_model("link_in.gltf", triangle_gltf("inside_link.bin"))).triangle_count() == 1);

  // Refused: every way out, for buffers and for images.
  REQUIRE(::symlink(l.secret.c_str(), (l.model + "/outside_link.bin").c_str()) == 0);
  REQUIRE(::symlink("..", (l.model + "/up").c_str()) == 0);
  struct Case {
    std::string buffer, image, expect;
  } cases[] = {
      {"../secret.bin", "", "'../secret.bin': a path that leaves the model's folder"},
      {"%2E%2E/secret.bin", "", "'../secret.bin': a path that leaves the model's folder"},
      {"sub/%2e%2e/%2e%2e/secret.bin", "", "leaves the model's folder"},
      {l.secret, "", "an absolute path"},
      {"file://" + l.secret, "", "the scheme 'file:'"},
      {"http://localhost/secret.bin", "", "the scheme 'http:'"},
      {"outside_link.bin", "", "'outside_link.bin': leads out of the model's folder through a symbolic link"},
      {"up/secret.bin", "", "'up/secret.bin': leads out of the model's folder through a symbolic link"},
      {"mesh.bin", "../secret.png", "'../secret.png': a path that leaves the model's folder"},
      {"mesh.bin", "../../../../../../../../proc/self/environ", "leaves the model's folder"},
      {"mesh.bin", "up/secret.png", "leads out of the model's folder through a symbolic link"},
      {"mesh.bin", "/proc/self/environ", "an absolute path"},
  };
  for (const Case& c : cases) {
    INFO("buffer " << c.buffer << ", image " << c.image);
    const std::string error = load_error(l.in_model("evil.gltf", triangle_gltf(c.buffer, c.image)));
    CHECK_THAT(error, Catch::StartsWith(l.model + "/evil.gltf: ") && Catch::Contains(c.expect) &&
                          Catch::Contains("a model may name only files in its own folder or below"));
    // Nothing of the target: not its size, nor tinygltf's wording with it.
    CHECK_THAT(error, !Catch::Contains("bytes") && !Catch::Contains("size") && !Catch::Contains("File read error"));
    // The same rule in a GLB, which may name files too.
    const std::string glb_error = load_error(l.in_model("evil.glb", meshsal_test::glb_file(triangle_gltf(c.buffer, c.image))));
    CHECK_THAT(glb_error, Catch::StartsWith(l.model + "/evil.glb: ") && Catch::Contains(c.expect));
  }
  // A file missing in the folder says so, whether or not one exists outside.
  CHECK_THAT(load_error(l.in_model("missing.gltf", triangle_gltf("nothing.bin"))),
             Catch::Contains("'nothing.bin': no such file in the model's folder"));
  // A GLB beside its buffer reads it as a .gltf does (the glTF format allows it).
  CHECK(load_mesh(l.in_model("ext.glb", meshsal_test::glb_file(triangle_gltf("mesh.bin")))).triangle_count() == 1);
}

TEST_CASE("gltf references: a buffer of the wrong length does not say the file's size", "[io][gltf][references]") {
  Layout l;
  l.in_model("long.bin", std::string(1571, 'x'));
  const std::string error = load_error(l.in_model("wrong.gltf", triangle_gltf("long.bin")));
  CHECK_THAT(error, Catch::Contains("not as long as its byteLength"));
  // The path may hold any digits (the temporary folder carries the pid): look past it.
  const std::string prefix = l.model + "/wrong.gltf: ";
  REQUIRE_THAT(error, Catch::StartsWith(prefix));
  const std::string message = error.substr(prefix.size());
  CHECK_THAT(message, !Catch::Contains("1571") && !Catch::Contains("requestedBytes"));
}

TEST_CASE("gltf references: one budget for all of a model's external files, not one per file", "[io][gltf][references]") {
  Layout l;
  // One 48-byte buffer file named by four buffers: 192 bytes read in all.
  std::string json = triangle_gltf("mesh.bin");
  const std::string one = "{\"byteLength\":48,\"uri\":\"mesh.bin\"}";
  json.replace(json.find("\"buffers\":["), std::string::npos, "\"buffers\":[" + one + "," + one + "," + one + "," + one + "]}");
  const std::string path = l.in_model("four.gltf", json);
  LoadOptions o;
  o.max_input_bytes = 192;
  CHECK(load_mesh(path, o).triangle_count() == 1);
  o.max_input_bytes = 191;  // each file alone fits; together they do not
  CHECK_THROWS_WITH(load_mesh(path, o), Catch::Contains("'mesh.bin': more than the 47 bytes left of the input limit"));
}

TEST_CASE("gltf references: a FIFO, a folder or a device named as a buffer is refused at once", "[io][gltf][references]") {
  Layout l;
  REQUIRE(::mkfifo((l.model + "/pipe.bin").c_str(), 0600) == 0);
  CHECK_THAT(load_error(l.in_model("fifo.gltf", triangle_gltf("pipe.bin"))), Catch::Contains("'pipe.bin': not a regular file"));
  CHECK_THAT(load_error(l.in_model("dir.gltf", triangle_gltf("sub"))), Catch::Contains("'sub': not a regular file"));
  REQUIRE(::symlink("/dev/zero", (l.model + "/zero.bin").c_str()) == 0);
  CHECK_THAT(load_error(l.in_model("dev.gltf", triangle_gltf("zero.bin"))), Catch::Contains("leads out of the model's folder"));
}

TEST_CASE("gltf references: the command writes nothing from a file outside the model's folder", "[io][gltf][references][cli]") {
  Layout l;
  const std::string evil = l.in_model("evil.gltf", triangle_gltf("mesh.bin", "../../../../../../../../proc/self/environ"));
  const auto dir = meshsal_test::scratch_dir("gltf_refs_cli");
  const std::string out = (dir / "out.glb").string();
  const meshsal_test::CliRun r = meshsal_test::run_cli("saliency " + meshsal_test::quoted(evil) + " -o " + meshsal_test::quoted(out), dir);
  CHECK(r.rc == 1);
  CHECK_THAT(r.err, Catch::Contains("leaves the model's folder"));
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("OBJ references: an mtllib outside the model's folder is refused by name", "[io][materials][references]") {
  const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  CHECK(load_mesh_bytes("mtllib m.mtl sub/n.mtl\n" + body, "a.obj").material_libraries.size() == 2);
  CHECK_THROWS_WITH(load_mesh_bytes("mtllib ../../etc/passwd\n" + body, "a.obj"),
                    Catch::Contains("a.obj: line 1: mtllib '../../etc/passwd': a path that leaves the model's folder"));
  CHECK_THROWS_WITH(load_mesh_bytes("mtllib ok.mtl /etc/passwd\n" + body, "a.obj"),
                    Catch::Contains("mtllib '/etc/passwd': an absolute path"));
}

TEST_CASE("OBJ references: a material library or texture that leads out of the folder refuses the model", "[io][materials][references]") {
  Layout l;
  const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
  // A library beside the model: read; one missing: noted, the model read.
  l.in_model("ok.mtl", "newmtl a\nKd 1 0 0\nmap_Kd sub/wood.png\n");
  const LoadedMesh ok = read_mesh(l.in_model("ok.obj", "mtllib ok.mtl missing.mtl\n" + body));
  CHECK(ok.mesh.material_library_text.size() == 2);
  CHECK(ok.report.unread == std::vector<std::string>{"material library 'missing.mtl': no such file in the model's folder"});
  // A library through a link out of the folder, or a texture named outside it: refused.
  l.root.write("outside.mtl", "newmtl a\n");
  REQUIRE(::symlink("../outside.mtl", (l.model + "/linked.mtl").c_str()) == 0);
  CHECK_THAT(load_error(l.in_model("linked.obj", "mtllib linked.mtl\n" + body)),
             Catch::Contains("material library 'linked.mtl': leads out of the model's folder through a symbolic link"));
  l.in_model("escape.mtl", "newmtl a\nmap_Kd -s 1 1 1 ../../secret.png\n");
  CHECK_THAT(load_error(l.in_model("escape.obj", "mtllib escape.mtl\n" + body)),
             Catch::Contains("material library 'escape.mtl': texture '../../secret.png': a path that leaves the model's folder"));
  l.in_model("absolute.mtl", "newmtl a\nbump /etc/hostname\n");
  CHECK_THAT(load_error(l.in_model("absolute.obj", "mtllib absolute.mtl\n" + body)),
             Catch::Contains("texture '/etc/hostname': an absolute path"));
}
