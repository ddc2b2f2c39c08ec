// meshsal: the self-contained HTML page of `meshsal view` and `batch --html`
// (write_view_page in meshsal.h): web/page.html filled in, the three.js viewer bundled at
// build time (web/viewer.js), the mesh embedded as a base64 GLB.
#include <cstdio>
#include <string>
#include <vector>

#include "api/page_template.h"
#include "core/html_text.h"
#include "core/mesh_points.h"
#include "io/atomic_write.h"
#include "io/colormap.h"
#include "io/mesh_io_internal.h"
#include "meshsal/meshsal.h"

#ifdef MESHSAL_WITH_VIEWER
#include "web_assets.h"  // kViewerBundle, kViewerPage (generated, CMakeLists.txt)
#endif

namespace meshsal {
namespace {

std::string base64(const std::string& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  size_t i = 0;
  auto byte = [&](size_t k) { return uint32_t(static_cast<unsigned char>(in[k])); };
  for (; i + 2 < in.size(); i += 3) {
    const uint32_t v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    out += t[v >> 18], out += t[(v >> 12) & 63], out += t[(v >> 6) & 63], out += t[v & 63];
  }
  if (i + 1 == in.size()) {
    const uint32_t v = byte(i) << 16;
    out += t[v >> 18], out += t[(v >> 12) & 63], out += "==";
  } else if (i + 2 == in.size()) {
    const uint32_t v = byte(i) << 16 | byte(i + 1) << 8;
    out += t[v >> 18], out += t[(v >> 12) & 63], out += t[(v >> 6) & 63], out += '=';
  }
  return out;
}

std::string number(double v, const char* format = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size()) s.replace(at, from.size(), to);
}

}  // namespace

bool built_with_viewer() {
#ifdef MESHSAL_WITH_VIEWER
  return true;
#else
  return false;
#endif
}

ViewPageReport write_view_page(const std::string& path, const Mesh& mesh, const std::vector<double>& saliency,
                               const ViewCamera& camera, const ViewPageOptions& options) {
#ifndef MESHSAL_WITH_VIEWER
  (void)mesh, (void)saliency, (void)camera, (void)options;
  throw Error(path + ": cannot write: this meshsal was built without the web viewer (web/node_modules was "
              "missing at build time: run tools/setup.sh, then build again)");
#else
  if (saliency.size() != mesh.vertex_count())
    throw Error(path + ": cannot write: " + std::to_string(saliency.size()) + " saliency values for " +
                std::to_string(mesh.vertex_count()) + " vertices");
  // The page's mesh: local coordinates with no node transform (the camera is in them, and
  // WebGL's floats would shake at survey coordinates); a copy simplified to max_faces when
  // the mesh is larger, the saliency carried along the collapses.
  Mesh shown;
  std::vector<double> shown_s;
  std::string note = options.note;
  ViewPageReport report;
  if (options.max_faces > 0 && mesh.triangle_count() > options.max_faces) {
    Mesh with_s = mesh;
    set_vertex_attribute(with_s, "\x01meshsal page saliency", saliency);
    SimplifyOptions so;
    so.target_faces = options.max_faces;
    shown = simplify_mesh(with_s, so).mesh;
    shown_s = take_vertex_attribute(shown, "\x01meshsal page saliency");
    report.simplified = true;
    // A closed surface keeps at least a tetrahedron's 4 faces, and a collapse may be refused
    // (a flip, the link condition): the count shown is the count said, budget or not.
    report.within_max_faces = shown.triangle_count() <= options.max_faces;
    char buf[300];
    if (report.within_max_faces)
      std::snprintf(buf, sizeof buf, "The page shows a copy simplified to %zu faces (plain quadrics, the saliency "
                    "carried): the mesh has %zu.", shown.triangle_count(), mesh.triangle_count());
    else
      std::snprintf(buf, sizeof buf, "The page shows a copy simplified to %zu faces, as far as the simplifier could "
                    "go towards the %zu asked (plain quadrics, the saliency carried): the mesh has %zu.",
                    shown.triangle_count(), options.max_faces, mesh.triangle_count());
    note += std::string(note.empty() ? "" : " ") + buf;
  } else {
    shown = mesh;
    shown_s = saliency;
  }
  report.shown_faces = shown.triangle_count();
  shown.attributes.clear();  // the page colours by saliency; nothing else is drawn
  shown.gltf_assets = nullptr;
  shown.triangle_material.clear();
  shown.materials.clear();
  shown.frame.clear();
  shown.source_positions.clear();
  for (double& o : shown.origin) o = 0;
  const std::vector<uint8_t> points = referenced_vertices(shown);
  GltfLevel level;
  level.mesh = &shown;
  level.saliency = &shown_s;
  level.is_point = &points;
  level.range = &options.range;
  const std::string glb = gltf_file_bytes(path, {level}, true);

  // The colour bar: the pictures' scale over the mesh's points, ticks where the square-root
  // position puts their values.
  const ColorLimits limits = colour_limits(saliency, referenced_vertices(mesh), options.range);
  std::string gradient = "linear-gradient(to right";
  for (int i = 0; i <= 20; ++i) {
    uint8_t rgb[3];
    colormap_rgb(i / 20.0, rgb);
    gradient += ", rgb(" + std::to_string(rgb[0]) + "," + std::to_string(rgb[1]) + "," + std::to_string(rgb[2]) + ") " +
                std::to_string(i * 5) + "%";
  }
  gradient += ")";
  std::string ticks;
  for (int i = 0; i <= 4; ++i) {
    const double t = i / 4.0, value = limits.lo + (limits.hi - limits.lo) * t * t;
    ticks += "<span style=\"left: " + number(100 * t, "%.1f") + "%\">" + html_escaped(number(value, "%.3g")) + "</span>";
  }
  std::string stats;
  for (const auto& [label, value] : options.stats)
    stats += "<tr><td>" + html_escaped(label) + "</td><td>" + html_escaped(value) + "</td></tr>";

  auto vec = [](const double* v) { return "[" + number(v[0], "%.17g") + "," + number(v[1], "%.17g") + "," + number(v[2], "%.17g") + "]"; };
  // Camera in the page's (local) coordinates: the mesh's own.
  const std::string data = "{\"glb\":\"" + base64(glb) + "\",\"camera\":{\"eye\":" + vec(camera.eye) +
                           ",\"target\":" + vec(camera.target) + ",\"up\":" + vec(camera.up) +
                           ",\"half_extent\":" + number(camera.half_extent, "%.17g") + "}}";
  std::string page = kViewerPage;
  std::string bundle = kViewerBundle;
  replace_all(bundle, "</script", "<\\/script");  // the bundle sits inside a <script> element
  const std::string title = html_escaped(options.title.empty() ? "mesh" : options.title);
  // One pass: a value (a title holding "@BUNDLE@", the bundle's own text) is never searched.
  page = fill_template(page, {{"@TITLE@", title},
                              {"@GRADIENT@", gradient},
                              {"@TICKS@", ticks},
                              {"@STATS@", stats},
                              {"@NOTE@", note.empty() ? "" : "<div class=\"note\">" + html_escaped(note) + "</div>"},
                              {"@DATA@", data},
                              {"@BUNDLE@", bundle}});
  write_file_atomically(path, [&](std::FILE* f) { write_all(f, page.data(), page.size(), path); });
  return report;
#endif
}

}  // namespace meshsal
