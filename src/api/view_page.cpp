// meshsal: the HTML page of `meshsal view` and `batch --html` (write_view_page in
// meshsal.h): web/page.html filled in, the three.js viewer bundled at build time
// (web/viewer.js) inline or beside the page (write_viewer_script), the mesh embedded as a
// base64 GLB made small for the page (page_glb).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "api/page_template.h"
#include "core/html_text.h"
#include "core/mesh_points.h"
#include "io/atomic_write.h"
#include "io/colormap.h"
#include "io/mesh_io_internal.h"
#include "meshsal/meshsal.h"

#include "view/camera.h"

#ifdef MESHSAL_PAGE_MESHOPT
#include <meshoptimizer.h>
#endif
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

void put(std::string& bin, const void* data, size_t bytes) {
  bin.append(static_cast<const char*>(data), bytes);
  while (bin.size() % 4) bin += '\0';
}

// The page's model as a GLB made for the page alone (the files meshsal writes keep
// write_gltf's): the vertices the triangles use, POSITION quantised to 16 bits of the
// bounding box's largest side (KHR_mesh_quantization: int16 normalised, the node's scale
// and translation giving back local coordinates; a step of 1/65534 of that side, below a
// pixel at any size a screen shows), _SALIENCY as float (the hover readout's values, exact
// to float), no normals (the viewer computes them) and the indices; with meshoptimizer at
// build time the streams go through EXT_meshopt_compression (three.js's GLTFLoader decodes
// it with MeshoptDecoder, bundled in the viewer), the triangles ordered for it first.
std::string page_glb(const Mesh& m, const std::vector<double>& s) {
  std::vector<uint32_t> idx = m.triangles;
  const size_t nv = m.vertex_count(), ni = idx.size();
#ifdef MESHSAL_PAGE_MESHOPT
  if (ni) meshopt_optimizeVertexCache(idx.data(), idx.data(), ni, nv);
#endif
  // Vertices numbered in order of first use (what meshopt_optimizeVertexFetch does).
  std::vector<uint32_t> remap(nv, UINT32_MAX), order;
  for (uint32_t& i : idx) {
    if (remap[i] == UINT32_MAX) remap[i] = uint32_t(order.size()), order.push_back(i);
    i = remap[i];
  }
  const size_t n = order.size();
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) {
      const double v = m.positions[3 * size_t(order[k]) + a];
      lo[a] = k ? std::min(lo[a], v) : v, hi[a] = k ? std::max(hi[a], v) : v;
    }
  double centre[3], half = 0;
  for (int a = 0; a < 3; ++a) centre[a] = (lo[a] + hi[a]) / 2, half = std::max(half, (hi[a] - lo[a]) / 2);
  if (!(half > 0)) half = 1;
  std::vector<int16_t> pos(4 * n, 0);
  int qlo[3] = {0, 0, 0}, qhi[3] = {0, 0, 0};
  for (size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) {
      const double t = (m.positions[3 * size_t(order[k]) + a] - centre[a]) / half;
      const int q = int(std::lround(std::clamp(t, -1.0, 1.0) * 32767));
      pos[4 * k + a] = int16_t(q);
      qlo[a] = k ? std::min(qlo[a], q) : q, qhi[a] = k ? std::max(qhi[a], q) : q;
    }
  std::vector<float> sal(n);
  for (size_t k = 0; k < n; ++k) sal[k] = float(s[order[k]]);
  const bool short_index = n <= 65535;
  std::vector<uint16_t> idx16;
  if (short_index) idx16.assign(idx.begin(), idx.end());

  struct Stream {
    const void* data;
    size_t count, stride;
    int target;  // 34962 vertices, 34963 indices
  };
  const Stream streams[3] = {{pos.data(), n, 8, 34962},
                             {sal.data(), n, 4, 34962},
                             {short_index ? static_cast<const void*>(idx16.data()) : idx.data(), ni,
                              short_index ? size_t(2) : size_t(4), 34963}};
  std::string bin, views;
  size_t raw_at = 0;
  for (int k = 0; k < 3; ++k) {
    const Stream& st = streams[k];
    const size_t bytes = st.count * st.stride;
    std::string view = "{\"buffer\":" + std::string(
#ifdef MESHSAL_PAGE_MESHOPT
                                           "1"
#else
                                           "0"
#endif
                                           ) + ",\"byteOffset\":" + std::to_string(
#ifdef MESHSAL_PAGE_MESHOPT
                                               raw_at
#else
                                               bin.size()
#endif
                                               ) + ",\"byteLength\":" + std::to_string(bytes) +
                       (st.target == 34962 ? ",\"byteStride\":" + std::to_string(st.stride) : std::string()) +
                       ",\"target\":" + std::to_string(st.target);
#ifdef MESHSAL_PAGE_MESHOPT
    std::vector<unsigned char> enc;
    if (st.target == 34962) {
      enc.resize(meshopt_encodeVertexBufferBound(st.count, st.stride));
      enc.resize(meshopt_encodeVertexBuffer(enc.data(), enc.size(), st.data, st.count, st.stride));
    } else {
      enc.resize(meshopt_encodeIndexBufferBound(ni, n));
      enc.resize(meshopt_encodeIndexBuffer(enc.data(), enc.size(), idx.data(), ni));
    }
    view += ",\"extensions\":{\"EXT_meshopt_compression\":{\"buffer\":0,\"byteOffset\":" + std::to_string(bin.size()) +
            ",\"byteLength\":" + std::to_string(enc.size()) + ",\"byteStride\":" + std::to_string(st.stride) +
            ",\"count\":" + std::to_string(st.count) + ",\"mode\":\"" +
            (st.target == 34962 ? "ATTRIBUTES" : "TRIANGLES") + "\"}}";
    put(bin, enc.data(), enc.size());
    raw_at += (bytes + 3) / 4 * 4;
#else
    put(bin, st.data, bytes);
#endif
    views += std::string(k ? "," : "") + view + "}";
  }
  auto ints = [](const int* v) {
    return "[" + std::to_string(v[0]) + "," + std::to_string(v[1]) + "," + std::to_string(v[2]) + "]";
  };
  const std::string exts =
#ifdef MESHSAL_PAGE_MESHOPT
      "[\"KHR_mesh_quantization\",\"EXT_meshopt_compression\"]";
#else
      "[\"KHR_mesh_quantization\"]";
#endif
  std::string json =
      "{\"asset\":{\"version\":\"2.0\",\"generator\":\"meshsal view page\"},\"extensionsUsed\":" + exts +
      ",\"extensionsRequired\":" + exts + ",\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,"
      "\"translation\":[" + number(centre[0], "%.17g") + "," + number(centre[1], "%.17g") + "," + number(centre[2], "%.17g") +
      "],\"scale\":[" + number(half, "%.17g") + "," + number(half, "%.17g") + "," + number(half, "%.17g") +
      "]}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"_SALIENCY\":1},\"indices\":2,\"mode\":4}]}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5122,\"normalized\":true,\"count\":" + std::to_string(n) +
      ",\"type\":\"VEC3\",\"min\":" + ints(qlo) + ",\"max\":" + ints(qhi) + "},{\"bufferView\":1,\"componentType\":5126,"
      "\"count\":" + std::to_string(n) + ",\"type\":\"SCALAR\"},{\"bufferView\":2,\"componentType\":" +
      (short_index ? "5123" : "5125") + ",\"count\":" + std::to_string(ni) + ",\"type\":\"SCALAR\"}],"
      "\"bufferViews\":[" + views + "],\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()) + "}" +
#ifdef MESHSAL_PAGE_MESHOPT
      ",{\"byteLength\":" + std::to_string(raw_at) + ",\"extensions\":{\"EXT_meshopt_compression\":{\"fallback\":true}}}" +
#endif
      "]}";
  while (json.size() % 4) json += ' ';
  std::string glb;
  auto u32 = [&glb](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };  // little-endian hosts
  glb += "glTF";
  u32(2);
  u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  u32(uint32_t(json.size()));
  glb += "JSON";
  glb += json;
  u32(uint32_t(bin.size()));
  glb += "BIN";
  glb += '\0';
  glb += bin;
  return glb;
}

#ifdef MESHSAL_WITH_VIEWER
// The bundle as it may sit inside a <script> element.
std::string viewer_bundle() {
  std::string bundle = kViewerBundle;
  replace_all(bundle, "</script", "<\\/script");
  return bundle;
}
#endif

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
  const std::string glb = page_glb(shown, shown_s);

  // The colour scale: the pictures' over the mesh's points (not the copy's), a value v at
  // the square-root position t = sqrt((v - lo) / (hi - lo)). The viewer colours the model,
  // places the bar's ticks and redraws for another range with the same rule, the colours
  // from `lut` (colormap_rgb at 256 positions), the percentiles from `quantiles` (the
  // mesh points' values at 0, 0.1, ..., 100 %).
  const std::vector<uint8_t> mesh_points = referenced_vertices(mesh);
  const ColorLimits limits = colour_limits(saliency, mesh_points, options.range);
  std::string gradient = "linear-gradient(to right";
  for (int i = 0; i <= 20; ++i) {
    uint8_t rgb[3];
    colormap_rgb(i / 20.0, rgb);
    gradient += ", rgb(" + std::to_string(rgb[0]) + "," + std::to_string(rgb[1]) + "," + std::to_string(rgb[2]) + ") " +
                std::to_string(i * 5) + "%";
  }
  gradient += ")";
  std::string lut;
  for (int i = 0; i < 256; ++i) {
    uint8_t rgb[3];
    colormap_rgb(i / 255.0, rgb);
    lut += (i ? "," : "") + std::to_string(rgb[0]) + "," + std::to_string(rgb[1]) + "," + std::to_string(rgb[2]);
  }
  std::vector<double> sorted;
  for (size_t v = 0; v < saliency.size(); ++v)
    if (mesh_points[v] && std::isfinite(saliency[v])) sorted.push_back(saliency[v]);
  std::sort(sorted.begin(), sorted.end());
  std::string quantiles;
  for (int k = 0; k <= 1000 && !sorted.empty(); ++k)
    quantiles += (k ? "," : "") + number(sorted[size_t(std::lround(k / 1000.0 * double(sorted.size() - 1)))], "%.9g");
  std::string stats;
  for (const auto& [label, value] : options.stats)
    stats += "<tr><td>" + html_escaped(label) + "</td><td>" + html_escaped(value) + "</td></tr>";

  auto vec = [](const double* v) { return "[" + number(v[0], "%.17g") + "," + number(v[1], "%.17g") + "," + number(v[2], "%.17g") + "]"; };
  // The frame of the angles (ViewFrame::axes for the camera's up axis): the viewer gives
  // the current camera's azimuth and elevation as direction_angles does.
  ViewFrame frame;
  set_up_axis(frame, camera.up_axis);
  static const char* const up_names[] = {"y", "-y", "z", "-z", "x", "-x"};
  // Camera in the page's (local) coordinates: the mesh's own.
  std::string data = "{\"glb\":\"" + base64(glb) + "\",\"camera\":{\"eye\":" + vec(camera.eye) +
                     ",\"target\":" + vec(camera.target) + ",\"up\":" + vec(camera.up) +
                     ",\"half_extent\":" + number(camera.half_extent, "%.17g") +
                     ",\"theta\":" + number(camera.view.theta, "%.17g") + ",\"phi\":" + number(camera.view.phi, "%.17g") +
                     ",\"up_axis\":\"" + up_names[int(camera.up_axis)] + "\",\"axes\":[" + vec(frame.axes[0]) + "," +
                     vec(frame.axes[1]) + "," + vec(frame.axes[2]) + "]";
  if (options.visible_score >= 0) data += ",\"U\":" + number(options.visible_score, "%.17g");
  if (options.visible_fraction >= 0) data += ",\"visible_fraction\":" + number(options.visible_fraction, "%.17g");
  data += "},\"scale\":{\"lo\":" + number(limits.lo, "%.17g") + ",\"hi\":" + number(limits.hi, "%.17g") +
          ",\"lut\":[" + lut + "],\"quantiles\":[" + quantiles + "]}}";
  std::string page = kViewerPage;
  // Inline, or the viewer file beside the page (a gallery's pages share one); a page whose
  // file is missing says so instead of staying blank.
  const std::string script =
      options.viewer_script.empty()
          ? "<script>" + viewer_bundle() + "</script>"
          : "<script src=\"" + html_escaped(options.viewer_script) +
                "\" onerror=\"document.body.dataset.status='error: the viewer script is missing';"
                "var e=document.getElementById('error');e.textContent='The viewer ' + this.getAttribute('src') + "
                "' (meshsal-viewer.js, written beside this page) could not be loaded.';e.hidden=false\"></script>";
  const std::string title = html_escaped(options.title.empty() ? "mesh" : options.title);
  // One pass: a value (a title holding "@BUNDLE@", the bundle's own text) is never searched.
  page = fill_template(page, {{"@TITLE@", title},
                              {"@GRADIENT@", gradient},
                              {"@STATS@", stats},
                              {"@NOTE@", note.empty() ? "" : "<div class=\"note\">" + html_escaped(note) + "</div>"},
                              {"@DATA@", data},
                              {"@BUNDLE@", script}});
  write_file_atomically(path, [&](std::FILE* f) { write_all(f, page.data(), page.size(), path); });
  return report;
#endif
}

void write_viewer_script(const std::string& path) {
#ifndef MESHSAL_WITH_VIEWER
  throw Error(path + ": cannot write: this meshsal was built without the web viewer (web/node_modules was "
              "missing at build time: run tools/setup.sh, then build again)");
#else
  const std::string bundle = kViewerBundle;
  write_file_atomically(path, [&](std::FILE* f) { write_all(f, bundle.data(), bundle.size(), path); });
#endif
}

}  // namespace meshsal
