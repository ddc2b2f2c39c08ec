// meshsal: a binary PLY (little or big endian, gzip or not) read front to back in chunks,
// for the out-of-core path: the file is never held whole in memory.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace meshsal {

class PlyStream {
 public:
  // Opens `path` and reads its header. Throws Error unless it is a binary PLY with a vertex
  // element holding x, y, z and a face element holding a vertex_indices (or vertex_index)
  // list, the vertices first.
  explicit PlyStream(const std::string& path);
  ~PlyStream();
  PlyStream(const PlyStream&) = delete;
  PlyStream& operator=(const PlyStream&) = delete;

  uint64_t vertex_count() const { return vertices_; }
  uint64_t face_count() const { return faces_; }   // polygons as the file has them
  bool double_positions() const { return double_xyz_; }
  // Whether every x, y, z value the file can hold is a float too (float32, or an integer
  // type of at most 16 bits): kept as floats, they are the values as read.
  bool positions_fit_float() const;

  // The next vertices' x, y, z (3 doubles each) into out, at most `max`; how many were
  // read (0 once every vertex has been).
  size_t read_vertices(double* out, size_t max);
  // The next polygons (at most `max`), fan-triangulated, appended to `triangles`; how many
  // polygons were read (0 at the end). Every index is checked against vertex_count().
  size_t read_faces(std::vector<uint32_t>& triangles, size_t max);

  // Whether the file reads in ranges (the ranks building a store each read their share):
  // uncompressed, every element before the faces of fixed-size records, and faces of the
  // common layout (the corner list alone: a 1-byte count, 4-byte indices) whose bytes are
  // exactly those of triangles (the file's size says so; read_faces still checks each).
  bool ranged() const;
  // Only where ranged(): the next read_vertices from vertex `first` on; the next read_faces
  // from face `first` on (the vertices are then taken as read).
  void seek_vertex(uint64_t first);
  void seek_face(uint64_t first);

  // True for a binary PLY (its first lines say so); false for anything else, which the
  // caller converts once. A binary PLY with a bad header is the constructor's Error.
  static bool readable(const std::string& path);

 private:
  struct Layout;
  void read_header();
  void find_ranges();
  void seek(uint64_t offset);
  void read_exact(void* to, size_t n);
  void skip_element(size_t e);
  bool ahead(size_t n);
  // The face loops' checks, with their messages: the file ended; the polygon's corner count
  // (polygon_size_problem); a corner's index as read, returned when it names a vertex.
  [[noreturn]] void ended() const;
  void check_corner_count(double n) const;
  uint32_t corner(double x) const;
  std::string path_;
  void* gz_ = nullptr;
  std::unique_ptr<Layout> layout_;
  uint64_t vertices_ = 0, faces_ = 0, vertices_read_ = 0, faces_read_ = 0;
  bool double_xyz_ = false;
};

}  // namespace meshsal
