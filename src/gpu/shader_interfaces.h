// meshsal: what the C++ side of every compute shader (shaders/*.comp) assumes about it, in
// one place: the push-constant block, a copy of the shader's `layout(push_constant) uniform
// Push` member for member, and how many storage buffers it binds (bindings 0..n-1, the
// buffers vk::DescriptorPool::bind is given). tests/gpu/test_shader_interfaces.cpp reads the
// compiled SPIR-V and checks each against it, so a change on one side only fails there.
// Plain C++ (no Vulkan): the test includes it without a device.
#pragma once
#include <cstdint>

namespace meshsal::gpu::shader {

// Push blocks. Each begins with {base, n}, which vk::dispatch fills in.
struct RangePush { uint32_t base, n; };
struct GroupsPush { uint32_t base, n, groups; };
struct ScalesPush { uint32_t base, n, nscales; };  // final_sum.comp
struct NearTiePush { uint32_t base, n, nmaps; };
struct RadixPush { uint32_t base, n, items, shift, first; };
struct GridKeyPush { uint32_t base, n, nx, ny, nz, pad; double h; };
struct CellKeyPush { uint32_t base, n, nx, ny, nz, pad; double cell; };
struct CellsPush { uint32_t base, n, count_slot, pad1; double minx, miny, minz; };  // fast_aggregate_cells.comp
// A dispatch over a bound n whose items' count the device wrote to counts[count_slot].
struct CountedPush { uint32_t base, n, count_slot; };
struct PairSumsPush { uint32_t base, n, first; };  // pair_sums.comp
struct RunPush { uint32_t base, n, count_slot, total_slot, flags; };  // run_heads/run_starts.comp
struct PiecesPush { uint32_t base, n, mode, piece, pieces_slot; };     // fast_pieces.comp
struct GroupKeyPush { uint32_t base, n, cells_slot, factor, dx, dy, gx, gy, gz; };
// curvature_face_key.comp: the Morton grid's minimum and steps per model unit.
struct MortonKeyPush {
  uint32_t base, n, pad0, pad1;
  double minx, miny, minz, scalex, scaley, scalez;
};
struct ScanPush { uint32_t base, nblocks, n, mode; };  // scan_blocks.comp
struct BoundPush { uint32_t base, n, nx, ny, nz, r, mode, most_slot; };  // fast_candidate_bound.comp
struct OriginPush { uint32_t base, n, pad0, pad1; double ox, oy, oz; };  // sorted_float, point_positions.comp
struct CornersPush { uint32_t base, n, vertices; };                     // point_flags.comp
struct QueryPush {
  uint32_t base, n, nx, ny, nz, dense, ord_lo, ord_hi;
  double h, cut2, radius, coef, shell2, shell_w;
};
struct FinishPush { uint32_t base, n, dense, offset; double inv_s2; };
struct CenterSurroundPush { uint32_t base, n, map, has_b; };
struct Fp64RatePush {
  uint32_t base, n, iterations;
  float mul, add;
};
struct RasterPush {
  uint32_t base, n, res, triangles, views, budget;  // n: invocations per view group
};
struct TestPush {
  uint32_t base, n, res, vertices;
  float tol;
  uint32_t views, budget;
};
// exposure_test.comp's: TestPush's members, then the weighting (ExposureWeighting's flags,
// 0 or 1) and the centre bias's 2 vx, 2 vy.
struct ExposurePush {
  uint32_t base, n, res, vertices;
  float tol;
  uint32_t views, budget, facing, centre;
  float two_vx, two_vy;
};
struct SelftestPush { uint32_t base, n; float a; };  // tests/gpu/test_gpu_selftest.cpp
// sweep.glsl's (every sweep*.comp).
struct SweepPush {
  uint32_t base, n, nx, ny, nz;
  uint32_t per_group;  // points per work group the dispatch is sized for (subgroup per point)
  uint32_t stride, nsig, nout, pad;
  double h, radius2;
};

// One shader's interface: its push block and its number of storage-buffer bindings.
// vk::cached_kernel<Shader>(...) creates the kernel from it.
template <class PushBlock, uint32_t Bindings>
struct Interface {
  using Push = PushBlock;
  static constexpr uint32_t bindings = Bindings;
};

// One line per shaders/NAME.comp (the test lists the same names).
using Curvature = Interface<CountedPush, 8>;
using CurvatureFaceKey = Interface<MortonKeyPush, 3>;
using CurvatureIncidence = Interface<RangePush, 4>;
using CurvatureRings = Interface<CountedPush, 8>;  // curvature.comp's bindings
using ExposureTest = Interface<ExposurePush, 8>;
using FastAggregateCells = Interface<CellsPush, 7>;
using FastAggregatePieces = Interface<CountedPush, 6>;
using FastCandidateBound = Interface<BoundPush, 4>;
using FastCellKey = Interface<CellKeyPush, 3>;
using FastCenterSurround = Interface<CenterSurroundPush, 4>;
using FastFinish = Interface<FinishPush, 8>;
using FastGroupCentroids = Interface<CountedPush, 6>;
using FastGroupKey = Interface<GroupKeyPush, 3>;
using FastPieces = Interface<PiecesPush, 8>;
using FastQuery = Interface<QueryPush, 8>;
using FinalSum = Interface<ScalesPush, 5>;
using Fp64Rate = Interface<Fp64RatePush, 1>;
using GlobalIndex = Interface<RangePush, 4>;
using GridGather = Interface<RangePush, 4>;
using GridKey = Interface<GridKeyPush, 4>;
using GridRadixCount = Interface<RadixPush, 2>;
using GridRadixScatter = Interface<RadixPush, 5>;
using LocalMax = Interface<GroupsPush, 7>;
using LocalMaxFaces = Interface<GroupsPush, 9>;
using MapMax = Interface<GroupsPush, 3>;
using MapMaxFinal = Interface<GroupsPush, 2>;
using Mbar = Interface<GroupsPush, 3>;
using NearTie = Interface<NearTiePush, 6>;
using NearTieFaces = Interface<NearTiePush, 8>;
using PairSums = Interface<PairSumsPush, 2>;
using PointFlags = Interface<CornersPush, 2>;
using PointPositions = Interface<OriginPush, 2>;
using RunHeads = Interface<RunPush, 3>;
using RunStarts = Interface<RunPush, 7>;
using ScanBlocks = Interface<ScanPush, 3>;
using Selftest = Interface<SelftestPush, 2>;
using SortedFloat = Interface<OriginPush, 2>;
using Sweep8 = Interface<SweepPush, 6>;
using Sweep8Rows = Interface<SweepPush, 6>;
using Sweep8Mixed = Interface<SweepPush, 8>;      // MIXED: the float points and error bounds
using Sweep8RowsMixed = Interface<SweepPush, 8>;
using Sweep8List = Interface<SweepPush, 8>;       // POINT_LIST: positions by vertex, the list
using SweepN = Interface<SweepPush, 6>;
using VisibilityRaster = Interface<RasterPush, 5>;
using VisibilityTest = Interface<TestPush, 6>;

}  // namespace meshsal::gpu::shader
