// Uses only <meshsal/meshsal.h>: a tetrahedron-like bump mesh, its saliency on the backend
// named on the command line, a simplification and a render. Prints one line of numbers
// that tests/package/run.sh checks.
#include <meshsal/meshsal.h>

#include <cmath>
#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
  // An octahedron subdivided once is enough to have curvature everywhere.
  const float p[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  const uint32_t t[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  meshsal::SaliencyOptions opt;
  opt.backend = argc > 1 && std::strcmp(argv[1], "gpu") == 0 ? meshsal::Backend::Gpu
                                                            : meshsal::Backend::Cpu;
  try {
    meshsal::SaliencyResult r = meshsal::compute_saliency(p, 6, t, 24, opt);
    meshsal::Mesh mesh = meshsal::make_mesh(p, 6, t, 24);
    meshsal::SimplifyOptions so;
    so.target_faces = 6;
    meshsal::Mesh out = meshsal::simplify_mesh(mesh, so).mesh;
    meshsal::RenderStyle style;
    style.size = 32;
    meshsal::Image img = meshsal::render_view(mesh, r.saliency, {}, style);
    std::printf("vulkan=%d backend=%s pairs=%llu eps=%.6f faces=%zu image=%dx%d\n",
                int(meshsal::built_with_vulkan()), r.backend_name.c_str(),
                static_cast<unsigned long long>(r.pairs), r.eps, out.triangle_count(), img.width,
                img.height);
  } catch (const meshsal::Error& e) {
    std::printf("error: %s\n", e.what());
    return 1;
  }
  return 0;
}
