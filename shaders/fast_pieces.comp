// CPU twin: the piece loop of fast_cell_runs() in src/gpu/gpu_fast_cells.cpp
// meshsal: --method fast, the pieces of the occupied cells on the device: a cell's sorted
// points [first, next first) cut every `piece` points from its first, so that no invocation
// of fast_aggregate_pieces.comp loops past lavapipe's 65,535 steps however many points share
// a cell. The cells are the runs of the sorted cell keys (run_heads.comp, run_starts.comp):
// cell_scan is the exclusive scan of their heads (the cell of slot i is cell_scan[i+1] - 1),
// cell_first their starts. mode 0: piece_head[i] = 1 where a piece starts; mode 1 (after a
// scan of those into piece_scan): piece_start[p] and piece_cell[p] of each piece p, cell_piece[c]
// = the first piece of cell c, and the closing entries; the piece count to counts[pieces_slot].
// The points (np = n) are the mesh points, which the sort put first.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer CellScan { uint cell_scan[]; };    // np + 1
layout(std430, binding = 1) readonly buffer CellFirst { uint cell_first[]; };  // cells + 1
layout(std430, binding = 2) buffer PieceHead { uint piece_head[]; };
layout(std430, binding = 3) readonly buffer PieceScan { uint piece_scan[]; };  // np + 1
layout(std430, binding = 4) writeonly buffer PieceStart { uint piece_start[]; };  // pieces + 1
layout(std430, binding = 5) writeonly buffer PieceCell { uint piece_cell[]; };
layout(std430, binding = 6) writeonly buffer CellPiece { uint cell_piece[]; };  // cells + 1
layout(std430, binding = 7) buffer Counts { uint counts[]; };
layout(push_constant) uniform Push { uint base; uint n; uint mode; uint piece; uint pieces_slot; } pc;
void main() {
  const uint i = pc.base + gl_GlobalInvocationID.x;
  if (i >= pc.n) return;
  const uint c = cell_scan[i + 1u] - 1u;
  const uint first = cell_first[c];
  if (pc.mode == 0u) {
    piece_head[i] = (i - first) % pc.piece == 0u ? 1u : 0u;
    return;
  }
  const uint p = piece_scan[i];
  if (piece_scan[i + 1u] > p) {
    piece_start[p] = i;
    piece_cell[p] = c;
    if (i == first) cell_piece[c] = p;
  }
  if (i == pc.n - 1u) {
    const uint pieces = piece_scan[pc.n];
    piece_start[pieces] = pc.n;
    cell_piece[cell_scan[pc.n]] = pieces;
    counts[pc.pieces_slot] = pieces;
  }
}
