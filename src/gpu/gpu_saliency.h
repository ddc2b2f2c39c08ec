// meshsal: SPEC section 1 on a Vulkan device, held to the CPU path (compute_saliency_cpu)
// to 1e-4 of each map's maximum, with the same local maxima, in both sweep precisions
// (options.precision, see saliency.h). The exact method's curvature and 1-rings come from the
// CPU (its bits are the CPU path's); the fast method's curvature runs on the device
// (gpu_curvature.h) and its suppression takes each vertex's triangles. The grid, the
// neighbour sweep, the raw maps, suppression, the final sum and the smoothed saliency
// G(S, 3 eps) run on the device.
#pragma once
#include <vector>

#include "meshsal/meshsal.h"
#include "saliency/saliency.h"
#include "gpu/vk_context.h"

namespace meshsal {

// The Vulkan devices (index, name, type, memory); throws Error when there is no driver.
std::vector<vk::DeviceInfo> gpu_devices();

// Saliency on Vulkan device options.device (-1: the best one; lavapipe when it is the only
// one). backend_name is the device name. validation: enable the Khronos validation layer
// (also on with MESHSAL_VALIDATION=1). Throws Error for a missing/failed/lost device or a
// mesh too large for the device.
SaliencyResult compute_saliency_gpu(const Mesh& mesh, const SaliencyOptions& options,
                                    bool validation = false);

// Opens device options.device in the process's cache (gpu_session.h) and runs what a
// saliency run with these options pays once per process, on a small synthetic scan: the
// pipelines' compiles, the fp64 probe (--precision auto) and the layout probe, for the
// method asked (both for Auto). A front end calls it on a thread while it reads the input,
// so that the run starts at once. Throws as compute_saliency_gpu does.
void warm_up_saliency_gpu(const SaliencyOptions& options);

// On device options.device in the cache, uploads a mesh's float positions (3 floats a
// vertex) or its triangles now, for the next saliency run there to take (gpu_prestage.h),
// where a run with these options uploads them (the fast method, and the exact one where
// the device computes its curvature); nothing otherwise. A front end calls them while it
// still reads the rest of the mesh (api/read_upload.h). True when it uploaded; throws as
// compute_saliency_gpu does.
bool prestage_positions_gpu(const SaliencyOptions& options, const float* positions, size_t vertex_count);
bool prestage_triangles_gpu(const SaliencyOptions& options, const uint32_t* triangles, size_t triangle_count);
// Frees what was uploaded ahead on device options.device and no run took.
void drop_prestaged_gpu(const SaliencyOptions& options);

// Same on an already open device (tests and the benchmark reuse one context).
SaliencyResult compute_saliency_gpu(vk::Context& ctx, const Mesh& mesh,
                                    const SaliencyOptions& options);

}  // namespace meshsal
