// Issue 38 (c): every compute shader's interface as the C++ side copies it by hand
// (gpu/shader_interfaces.h) against the compiled shader itself. The SPIR-V the build embeds
// (build/shaders/NAME_comp.h) is read word by word; no Vulkan device is needed. For each
// shader: the push-constant block has the C++ struct's size, and each member the C++
// member's name and offset; the storage buffers are bindings 0..n-1 with n what the C++ side
// binds (Interface::bindings).
//
// A shader whose push block or buffers change fails here until its line in
// gpu/shader_interfaces.h (and its member list below) says the same.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "gpu/shader_interfaces.h"

#include "curvature_comp.h"
#include "curvature_face_key_comp.h"
#include "curvature_incidence_comp.h"
#include "curvature_rings_comp.h"
#include "exposure_test_comp.h"
#include "fast_aggregate_cells_comp.h"
#include "fast_aggregate_pieces_comp.h"
#include "fast_candidate_bound_comp.h"
#include "fast_cell_key_comp.h"
#include "fast_center_surround_comp.h"
#include "fast_finish_comp.h"
#include "fast_group_centroids_comp.h"
#include "fast_group_key_comp.h"
#include "fast_pieces_comp.h"
#include "fast_query_comp.h"
#include "final_sum_comp.h"
#include "fp64_rate_comp.h"
#include "global_index_comp.h"
#include "grid_gather_comp.h"
#include "grid_key_comp.h"
#include "grid_radix_count_comp.h"
#include "grid_radix_scatter_comp.h"
#include "local_max_comp.h"
#include "local_max_faces_comp.h"
#include "map_max_comp.h"
#include "map_max_final_comp.h"
#include "mbar_comp.h"
#include "near_tie_comp.h"
#include "near_tie_faces_comp.h"
#include "pair_sums_comp.h"
#include "point_flags_comp.h"
#include "point_positions_comp.h"
#include "run_heads_comp.h"
#include "run_starts_comp.h"
#include "scan_blocks_comp.h"
#include "selftest_comp.h"
#include "sorted_float_comp.h"
#include "sweep8_comp.h"
#include "sweep8_list_comp.h"
#include "sweep8_mixed_comp.h"
#include "sweep8_rows_comp.h"
#include "sweep8_rows_mixed_comp.h"
#include "sweepn_comp.h"
#include "visibility_raster_comp.h"
#include "visibility_test_comp.h"

namespace {

namespace shader = meshsal::gpu::shader;

// --- what a SPIR-V module says about its interface ---------------------------------------

struct SpirvMember {
  std::string name;
  uint32_t offset = 0, size = 0, align = 0;  // align: of its scalars (std430 push blocks)
};

struct SpirvInterface {
  bool has_push = false;
  std::vector<SpirvMember> push;   // in declaration order
  std::vector<uint32_t> bindings;  // of the storage buffers, sorted
  std::string error;               // what could not be read
};

// SPIR-V opcodes, decorations and storage classes used below (the SPIR-V specification,
// section 3).
enum : uint32_t {
  OpName = 5, OpMemberName = 6, OpTypeInt = 21, OpTypeFloat = 22, OpTypeVector = 23,
  OpTypeArray = 28, OpTypeRuntimeArray = 29, OpTypeStruct = 30, OpTypePointer = 32,
  OpConstant = 43, OpVariable = 59, OpDecorate = 71, OpMemberDecorate = 72,
  DecorationBufferBlock = 3, DecorationArrayStride = 6, DecorationBinding = 33, DecorationOffset = 35,
  StorageUniform = 2, StoragePushConstant = 9, StorageStorageBuffer = 12,
};

std::string literal_string(const uint32_t* words, size_t count) {
  std::string s;
  for (size_t i = 0; i < count; ++i)
    for (int b = 0; b < 4; ++b) {
      const char c = char((words[i] >> (8 * b)) & 0xff);
      if (c == 0) return s;
      s += c;
    }
  return s;
}

SpirvInterface read_spirv(const uint32_t* code, size_t bytes) {
  SpirvInterface out;
  const size_t n = bytes / 4;
  if (n < 5 || code[0] != 0x07230203u) {
    out.error = "not SPIR-V (magic number)";
    return out;
  }
  struct Type {
    uint32_t op = 0;
    std::vector<uint32_t> args;  // the instruction's words after the result id
  };
  std::map<uint32_t, Type> types;
  std::map<uint32_t, uint32_t> constants;                         // id -> value (32-bit)
  std::map<uint32_t, uint32_t> binding, array_stride;             // id -> decoration value
  std::map<uint32_t, bool> buffer_block;                          // struct id
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> member_offset;
  std::map<std::pair<uint32_t, uint32_t>, std::string> member_name;
  std::vector<std::pair<uint32_t, uint32_t>> variables;           // (pointer type, id)
  for (size_t i = 5; i < n;) {
    const uint32_t count = code[i] >> 16, op = code[i] & 0xffff;
    if (count == 0 || i + count > n) {
      out.error = "malformed instruction at word " + std::to_string(i);
      return out;
    }
    const uint32_t* w = &code[i];
    switch (op) {
      case OpMemberName: member_name[{w[1], w[2]}] = literal_string(w + 3, count - 3); break;
      case OpTypeInt: case OpTypeFloat: case OpTypeVector: case OpTypeArray: case OpTypeRuntimeArray:
      case OpTypeStruct: case OpTypePointer:
        types[w[1]] = {op, std::vector<uint32_t>(w + 2, w + count)};
        break;
      case OpConstant: if (count >= 4) constants[w[2]] = w[3]; break;
      case OpVariable: variables.push_back({w[1], w[2]}); break;
      case OpDecorate:
        if (w[2] == DecorationBinding) binding[w[1]] = w[3];
        if (w[2] == DecorationArrayStride) array_stride[w[1]] = w[3];
        if (w[2] == DecorationBufferBlock) buffer_block[w[1]] = true;
        break;
      case OpMemberDecorate:
        if (w[3] == DecorationOffset) member_offset[{w[1], w[2]}] = w[4];
        break;
      default: break;
    }
    i += count;
  }
  // size and scalar alignment of a type inside a push block
  std::function<std::pair<uint32_t, uint32_t>(uint32_t)> size_of = [&](uint32_t id) -> std::pair<uint32_t, uint32_t> {
    const Type& t = types[id];
    switch (t.op) {
      case OpTypeInt: case OpTypeFloat: return {t.args[0] / 8, t.args[0] / 8};
      case OpTypeVector: {
        const auto [s, a] = size_of(t.args[0]);
        return {s * t.args[1], a};
      }
      case OpTypeArray: {
        const auto [s, a] = size_of(t.args[0]);
        const uint32_t stride = array_stride.count(id) ? array_stride[id] : s;
        return {stride * constants[t.args[1]], a};
      }
      default: out.error = "a push-block member of an unexpected type"; return {0, 1};
    }
  };
  for (const auto& [pointer, id] : variables) {
    const Type& p = types[pointer];
    if (p.op != OpTypePointer) continue;
    const uint32_t storage = p.args[0], pointee = p.args[1];
    if (storage == StoragePushConstant) {
      const Type& s = types[pointee];
      out.has_push = true;
      for (uint32_t m = 0; m < s.args.size(); ++m) {
        SpirvMember member;
        member.name = member_name[{pointee, m}];
        member.offset = member_offset[{pointee, m}];
        std::tie(member.size, member.align) = size_of(s.args[m]);
        out.push.push_back(member);
      }
    } else if (storage == StorageStorageBuffer || (storage == StorageUniform && buffer_block[pointee])) {
      if (!binding.count(id)) {
        out.error = "a storage buffer without a binding";
        continue;
      }
      out.bindings.push_back(binding[id]);
    }
  }
  std::sort(out.bindings.begin(), out.bindings.end());
  return out;
}

// --- what the C++ side says -----------------------------------------------------------------

struct Member {
  const char* name;
  size_t offset;
};
#define MEMBER(T, m) Member{#m, offsetof(T, m)}

// The members of each push block, in declaration order: a member added to a struct in
// gpu/shader_interfaces.h goes here too (the size check below fails until it does).
template <class P> std::vector<Member> members_of();
using namespace meshsal::gpu::shader;
template <> std::vector<Member> members_of<RangePush>() { return {MEMBER(RangePush, base), MEMBER(RangePush, n)}; }
template <> std::vector<Member> members_of<GroupsPush>() {
  return {MEMBER(GroupsPush, base), MEMBER(GroupsPush, n), MEMBER(GroupsPush, groups)};
}
template <> std::vector<Member> members_of<ScalesPush>() {
  return {MEMBER(ScalesPush, base), MEMBER(ScalesPush, n), MEMBER(ScalesPush, nscales)};
}
template <> std::vector<Member> members_of<NearTiePush>() {
  return {MEMBER(NearTiePush, base), MEMBER(NearTiePush, n), MEMBER(NearTiePush, nmaps)};
}
template <> std::vector<Member> members_of<RadixPush>() {
  return {MEMBER(RadixPush, base), MEMBER(RadixPush, n), MEMBER(RadixPush, items), MEMBER(RadixPush, shift),
          MEMBER(RadixPush, first)};
}
template <> std::vector<Member> members_of<GridKeyPush>() {
  return {MEMBER(GridKeyPush, base), MEMBER(GridKeyPush, n), MEMBER(GridKeyPush, nx), MEMBER(GridKeyPush, ny),
          MEMBER(GridKeyPush, nz), MEMBER(GridKeyPush, pad), MEMBER(GridKeyPush, h)};
}
template <> std::vector<Member> members_of<CellKeyPush>() {
  return {MEMBER(CellKeyPush, base), MEMBER(CellKeyPush, n), MEMBER(CellKeyPush, nx), MEMBER(CellKeyPush, ny),
          MEMBER(CellKeyPush, nz), MEMBER(CellKeyPush, pad), MEMBER(CellKeyPush, cell)};
}
template <> std::vector<Member> members_of<CellsPush>() {
  return {MEMBER(CellsPush, base), MEMBER(CellsPush, n), MEMBER(CellsPush, count_slot), MEMBER(CellsPush, pad1),
          MEMBER(CellsPush, minx), MEMBER(CellsPush, miny), MEMBER(CellsPush, minz)};
}
template <> std::vector<Member> members_of<CountedPush>() {
  return {MEMBER(CountedPush, base), MEMBER(CountedPush, n), MEMBER(CountedPush, count_slot)};
}
template <> std::vector<Member> members_of<PairSumsPush>() {
  return {MEMBER(PairSumsPush, base), MEMBER(PairSumsPush, n), MEMBER(PairSumsPush, first)};
}
template <> std::vector<Member> members_of<RunPush>() {
  return {MEMBER(RunPush, base), MEMBER(RunPush, n), MEMBER(RunPush, count_slot), MEMBER(RunPush, total_slot),
          MEMBER(RunPush, flags)};
}
template <> std::vector<Member> members_of<PiecesPush>() {
  return {MEMBER(PiecesPush, base), MEMBER(PiecesPush, n), MEMBER(PiecesPush, mode), MEMBER(PiecesPush, piece),
          MEMBER(PiecesPush, pieces_slot)};
}
template <> std::vector<Member> members_of<GroupKeyPush>() {
  return {MEMBER(GroupKeyPush, base), MEMBER(GroupKeyPush, n), MEMBER(GroupKeyPush, cells_slot),
          MEMBER(GroupKeyPush, factor), MEMBER(GroupKeyPush, dx), MEMBER(GroupKeyPush, dy),
          MEMBER(GroupKeyPush, gx), MEMBER(GroupKeyPush, gy), MEMBER(GroupKeyPush, gz)};
}
template <> std::vector<Member> members_of<MortonKeyPush>() {
  return {MEMBER(MortonKeyPush, base),   MEMBER(MortonKeyPush, n),      MEMBER(MortonKeyPush, pad0),
          MEMBER(MortonKeyPush, pad1),   MEMBER(MortonKeyPush, minx),   MEMBER(MortonKeyPush, miny),
          MEMBER(MortonKeyPush, minz),   MEMBER(MortonKeyPush, scalex), MEMBER(MortonKeyPush, scaley),
          MEMBER(MortonKeyPush, scalez)};
}
template <> std::vector<Member> members_of<ScanPush>() {
  return {MEMBER(ScanPush, base), MEMBER(ScanPush, nblocks), MEMBER(ScanPush, n), MEMBER(ScanPush, mode)};
}
template <> std::vector<Member> members_of<BoundPush>() {
  return {MEMBER(BoundPush, base), MEMBER(BoundPush, n), MEMBER(BoundPush, nx), MEMBER(BoundPush, ny),
          MEMBER(BoundPush, nz), MEMBER(BoundPush, r), MEMBER(BoundPush, mode), MEMBER(BoundPush, most_slot)};
}
template <> std::vector<Member> members_of<OriginPush>() {
  return {MEMBER(OriginPush, base), MEMBER(OriginPush, n), MEMBER(OriginPush, pad0), MEMBER(OriginPush, pad1),
          MEMBER(OriginPush, ox), MEMBER(OriginPush, oy), MEMBER(OriginPush, oz)};
}
template <> std::vector<Member> members_of<CornersPush>() {
  return {MEMBER(CornersPush, base), MEMBER(CornersPush, n), MEMBER(CornersPush, vertices)};
}
template <> std::vector<Member> members_of<QueryPush>() {
  return {MEMBER(QueryPush, base), MEMBER(QueryPush, n), MEMBER(QueryPush, nx), MEMBER(QueryPush, ny),
          MEMBER(QueryPush, nz), MEMBER(QueryPush, dense), MEMBER(QueryPush, ord_lo), MEMBER(QueryPush, ord_hi),
          MEMBER(QueryPush, h), MEMBER(QueryPush, cut2), MEMBER(QueryPush, radius), MEMBER(QueryPush, coef),
          MEMBER(QueryPush, shell2), MEMBER(QueryPush, shell_w)};
}
template <> std::vector<Member> members_of<FinishPush>() {
  return {MEMBER(FinishPush, base), MEMBER(FinishPush, n), MEMBER(FinishPush, dense), MEMBER(FinishPush, offset),
          MEMBER(FinishPush, inv_s2)};
}
template <> std::vector<Member> members_of<CenterSurroundPush>() {
  return {MEMBER(CenterSurroundPush, base), MEMBER(CenterSurroundPush, n), MEMBER(CenterSurroundPush, map),
          MEMBER(CenterSurroundPush, has_b)};
}
template <> std::vector<Member> members_of<Fp64RatePush>() {
  return {MEMBER(Fp64RatePush, base), MEMBER(Fp64RatePush, n), MEMBER(Fp64RatePush, iterations),
          MEMBER(Fp64RatePush, mul), MEMBER(Fp64RatePush, add)};
}
template <> std::vector<Member> members_of<RasterPush>() {
  return {MEMBER(RasterPush, base), MEMBER(RasterPush, n), MEMBER(RasterPush, res), MEMBER(RasterPush, triangles),
          MEMBER(RasterPush, views), MEMBER(RasterPush, budget)};
}
template <> std::vector<Member> members_of<TestPush>() {
  return {MEMBER(TestPush, base), MEMBER(TestPush, n), MEMBER(TestPush, res), MEMBER(TestPush, vertices),
          MEMBER(TestPush, tol), MEMBER(TestPush, views), MEMBER(TestPush, budget)};
}
template <> std::vector<Member> members_of<ExposurePush>() {
  return {MEMBER(ExposurePush, base), MEMBER(ExposurePush, n), MEMBER(ExposurePush, res),
          MEMBER(ExposurePush, vertices), MEMBER(ExposurePush, tol), MEMBER(ExposurePush, views),
          MEMBER(ExposurePush, budget), MEMBER(ExposurePush, facing), MEMBER(ExposurePush, centre),
          MEMBER(ExposurePush, two_vx), MEMBER(ExposurePush, two_vy)};
}
template <> std::vector<Member> members_of<SelftestPush>() {
  return {MEMBER(SelftestPush, base), MEMBER(SelftestPush, n), MEMBER(SelftestPush, a)};
}
template <> std::vector<Member> members_of<SweepPush>() {
  return {MEMBER(SweepPush, base), MEMBER(SweepPush, n), MEMBER(SweepPush, nx), MEMBER(SweepPush, ny),
          MEMBER(SweepPush, nz), MEMBER(SweepPush, per_group), MEMBER(SweepPush, stride), MEMBER(SweepPush, nsig),
          MEMBER(SweepPush, nout), MEMBER(SweepPush, pad), MEMBER(SweepPush, h), MEMBER(SweepPush, radius2)};
}

struct Case {
  std::string name;  // shaders/NAME.comp
  const uint32_t* spirv;
  size_t spirv_bytes;
  uint32_t bindings;
  size_t push_size;
  std::vector<Member> members;
};

template <class Shader>
Case make_case(const char* name, const uint32_t* spirv, size_t spirv_bytes) {
  using Push = typename Shader::Push;
  return {name, spirv, spirv_bytes, Shader::bindings, sizeof(Push), members_of<Push>()};
}
#define SHADER(Iface, name) make_case<shader::Iface>(#name, spv_##name##_comp, sizeof spv_##name##_comp)

// Every shaders/*.comp, with the interface the C++ side uses it with.
std::vector<Case> all_cases() {
  return {
      SHADER(Curvature, curvature),                     SHADER(CurvatureFaceKey, curvature_face_key),
      SHADER(CurvatureIncidence, curvature_incidence),   SHADER(CurvatureRings, curvature_rings),
      SHADER(ExposureTest, exposure_test),
      SHADER(FastAggregateCells, fast_aggregate_cells), SHADER(FastAggregatePieces, fast_aggregate_pieces),
      SHADER(FastCandidateBound, fast_candidate_bound),
      SHADER(FastCellKey, fast_cell_key),               SHADER(FastCenterSurround, fast_center_surround),
      SHADER(FastFinish, fast_finish),                  SHADER(FastGroupCentroids, fast_group_centroids),
      SHADER(FastGroupKey, fast_group_key),             SHADER(FastPieces, fast_pieces),
      SHADER(FastQuery, fast_query),                    SHADER(FinalSum, final_sum),
      SHADER(Fp64Rate, fp64_rate),                      SHADER(GlobalIndex, global_index),
      SHADER(GridGather, grid_gather),                  SHADER(GridKey, grid_key),
      SHADER(GridRadixCount, grid_radix_count),         SHADER(GridRadixScatter, grid_radix_scatter),
      SHADER(LocalMax, local_max),                      SHADER(LocalMaxFaces, local_max_faces),
      SHADER(MapMax, map_max),                          SHADER(MapMaxFinal, map_max_final),
      SHADER(Mbar, mbar),                               SHADER(NearTie, near_tie),
      SHADER(NearTieFaces, near_tie_faces),
      SHADER(PairSums, pair_sums),                      SHADER(PointFlags, point_flags),
      SHADER(PointPositions, point_positions),
      SHADER(RunHeads, run_heads),                      SHADER(RunStarts, run_starts),
      SHADER(ScanBlocks, scan_blocks),                  SHADER(Selftest, selftest),
      SHADER(SortedFloat, sorted_float),
      SHADER(Sweep8, sweep8),                           SHADER(Sweep8List, sweep8_list),
      SHADER(Sweep8Mixed, sweep8_mixed),                SHADER(Sweep8Rows, sweep8_rows),
      SHADER(Sweep8RowsMixed, sweep8_rows_mixed),       SHADER(SweepN, sweepn),
      SHADER(VisibilityRaster, visibility_raster),      SHADER(VisibilityTest, visibility_test),
  };
}

}  // namespace

TEST_CASE("every shaders/*.comp has a C++ interface to check", "[shaders]") {
  std::vector<std::string> listed;
  for (const Case& c : all_cases()) listed.push_back(c.name + ".comp");
  std::sort(listed.begin(), listed.end());
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(std::string(MESHSAL_SOURCE_DIR) + "/shaders"))
    if (e.path().extension() == ".comp") found.push_back(e.path().filename().string());
  std::sort(found.begin(), found.end());
  CHECK(listed == found);
}

TEST_CASE("push blocks and storage buffers match the compiled shaders", "[shaders]") {
  for (const Case& c : all_cases()) {
    SECTION(c.name) {
      const SpirvInterface s = read_spirv(c.spirv, c.spirv_bytes);
      INFO("shaders/" << c.name << ".comp against gpu/shader_interfaces.h");
      REQUIRE(s.error.empty());
      // Storage buffers: bindings 0..n-1, n as bound by the C++ side.
      std::vector<uint32_t> want(c.bindings);
      for (uint32_t i = 0; i < c.bindings; ++i) want[i] = i;
      CHECK(s.bindings == want);
      // The push block: members by name and offset, and its size (std430: rounded up to the
      // largest scalar alignment, as a C++ struct of these members is).
      REQUIRE(s.has_push);
      uint32_t end = 0, align = 1;
      std::ostringstream shader_members, cpp_members;
      for (const SpirvMember& m : s.push) {
        end = std::max(end, m.offset + m.size);
        align = std::max(align, m.align);
        shader_members << m.name << "@" << m.offset << " ";
      }
      for (const Member& m : c.members) cpp_members << m.name << "@" << m.offset << " ";
      INFO("shader members: " << shader_members.str());
      INFO("C++ members:    " << cpp_members.str());
      CHECK(shader_members.str() == cpp_members.str());
      const uint32_t shader_size = (end + align - 1) / align * align;
      CHECK(shader_size == c.push_size);
    }
  }
}
