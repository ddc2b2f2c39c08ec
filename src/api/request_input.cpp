// meshsal: the meshes a request reads: plainly (S, a saliency PLY, the views) and with its
// attributes (the mesh outputs that carry them), each only when an output needs it.
#include <string>

#include "api/request_parts.h"
#include "core/timer.h"
#include "io/read_observer.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// The format of a mesh file's name, a trailing .gz dropped.
std::string input_format(const std::string& path) {
  std::string name = path;
  if (name.size() > 3 && (name.compare(name.size() - 3, 3, ".gz") == 0 || name.compare(name.size() - 3, 3, ".GZ") == 0))
    name.resize(name.size() - 3);
  return mesh_output_format(name);
}

// The notes of a read: STL corners welded, and (with attributes) what the file holds that
// no output carries.
void note_read(RequestRun& run, const LoadReport& report, const Mesh& mesh, bool attributes) {
  const std::string& in = run.request.input;
  if (report.welded_corners)
    add_note(run, in + ": welded " + std::to_string(report.welded_corners) + " STL corners into " +
                      std::to_string(mesh.vertex_count()) + " shared vertices");
  if (attributes && !report.unread.empty()) {
    std::string what;
    for (size_t i = 0; i < report.unread.size(); ++i) what += (i ? ", " : "") + report.unread[i];
    add_note(run, in + ": not carried to the output: " + what);
  }
}

}  // namespace

bool needs_plain_mesh(const Request& r) {
  if (r.out_of_core.memory_limit > 0) return false;
  const bool saliency_ply = !r.saliency_output.empty() && mesh_output_format(r.saliency_output) == ".ply";
  return saliency_ply || !r.page_output.empty() || !r.picture_output.empty() || !r.map_output.empty() || r.find_view;
}

bool needs_attributed_mesh(const Request& r) {
  if (r.out_of_core.memory_limit > 0) return false;
  const bool saliency_other = !r.saliency_output.empty() && mesh_output_format(r.saliency_output) != ".ply";
  return saliency_other || !r.simplified_output.empty() || !r.lod_output.empty() || r.simplify_in_memory;
}

void read_input(RequestRun& run) {
  const Request& r = run.request;
  const Timer t;
  if (needs_plain_mesh(r)) {
    if (r.mesh) {
      run.plain = r.mesh;
    } else {
      // Where the views may take S from the input, it is read with its attributes, to see
      // whether it holds S (a PLY's quality, a glTF's _SALIENCY), then without them.
      const std::string format = input_format(r.input);
      LoadOptions o = r.load;
      o.attributes = r.saliency_from_input && (format == ".ply" || format == ".glb" || format == ".gltf");
      LoadedMesh read = read_mesh_observed(r.input, o, run.read_observer);
      run.read_observer = nullptr;
      const LoadReport& report = read.report;
      run.plain_read = std::move(read.mesh);
      for (const VertexAttribute& a : run.plain_read.attributes) run.input_has_saliency |= a.name == kSaliencyAttribute;
      run.plain_read.attributes.clear();
      run.plain_read.material_library_text.clear();
      note_read(run, report, run.plain_read, false);
      run.result.load = report;
      run.plain_report = report;
      run.plain = &run.plain_read;
    }
  }
  if (needs_attributed_mesh(r)) {
    if (r.attributed) {
      run.attributed = r.attributed;
    } else if (r.mesh && (r.input.empty() || input_format(r.input) == ".stl" || !r.mesh->attributes.empty())) {
      run.attributed = r.mesh;  // a mesh in memory carries what it has (an STL has nothing more)
    } else {
      // The input read again with its attributes (a caller gave it read plainly).
      LoadOptions o = r.load;
      o.attributes = true;
      LoadedMesh read = read_mesh_observed(r.input, o, run.read_observer);
      run.read_observer = nullptr;
      const LoadReport& report = read.report;
      run.attributed_read = std::move(read.mesh);
      note_read(run, report, run.attributed_read, !run.plain);
      run.result.load = report;
      run.attributed = &run.attributed_read;
    }
  }
  run.result.load_seconds = t.seconds();
}

}  // namespace meshsal
