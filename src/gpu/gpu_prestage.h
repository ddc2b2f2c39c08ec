// meshsal: a mesh's float positions and triangles put on the device ahead of the saliency
// call that takes them, so that their upload overlaps the reading of the file
// (api/read_upload.h starts it while a PLY's faces are still parsed).
//
// The buffers are held on the context (vk::Context::prestaged) under a key of their bytes.
// The next compute_saliency_gpu on that context takes a held buffer only where its mesh's
// array gives the same key (the same kind, count and bytes: the buffer the upload would
// make), uploads as before otherwise, and frees what it did not take (so two runs sharing a
// device at once may free each other's: they upload again, with the same result). A key
// is 64 bits of a hash, not a copy: arrays that differ and still agree in it are a 2^-64
// chance.
#pragma once
#include <cstddef>
#include <cstdint>

#include "gpu/vk_buffer.h"
#include "meshsal/meshsal.h"

namespace meshsal::gpu {

// A hash of `bytes` bytes at `data`, the same for every thread count (blocks of 1 MiB
// hashed on `threads`, then combined in order; 0: the process's share of the cores).
uint64_t array_key(const void* data, size_t bytes, unsigned threads = 0);

// Uploads now what upload_float_positions (gpu_fast.h) would upload for a mesh with these
// positions (3 floats a vertex, Mesh::positions), and holds it on `ctx`.
void prestage_float_positions(vk::Context& ctx, const float* positions, size_t vertex_count, unsigned threads = 0);
// The same for the triangles (3 indices each, Mesh::triangles), as DeviceCurvature holds them.
void prestage_triangles(vk::Context& ctx, const uint32_t* triangles, size_t triangle_count, unsigned threads = 0);

// The float positions (vec4 a vertex) and the triangles of `mesh` on the device: the held
// buffer whose key the mesh's array gives, taken off the context, or else uploaded now.
vk::Buffer float_positions(vk::Context& ctx, const Mesh& mesh, unsigned threads = 0);
vk::Buffer mesh_triangles(vk::Context& ctx, const Mesh& mesh, unsigned threads = 0);

// Frees every held buffer (what no call took).
void drop_prestaged(vk::Context& ctx);
// Device bytes the held buffers take.
uint64_t prestaged_bytes(const vk::Context& ctx);

}  // namespace meshsal::gpu
