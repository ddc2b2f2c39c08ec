#include "io/ply_stream.h"

#include <sys/stat.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <sstream>

#include "io/mesh_io_internal.h"
#include "io/ply_types.h"
#include "meshsal/meshsal.h"

namespace meshsal {

namespace {

struct Property {
  std::string name;
  PlyType type = PlyType::Float32;  // scalar type, or the list's item type
  bool is_list = false;
  PlyType count = PlyType::UInt8;   // a list's count type
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

}  // namespace

struct PlyStream::Layout {
  std::vector<Element> elements;
  size_t vertex = SIZE_MAX, face = SIZE_MAX;  // element indices
  size_t next = 0;                            // the element the stream stands at
  bool swap = false;
  size_t vertex_bytes = 0;                    // one vertex record
  size_t xyz_offset[3] = {0, 0, 0};
  PlyType xyz_type[3] = {PlyType::Float32, PlyType::Float32, PlyType::Float32};
  bool has_xyz[3] = {false, false, false};
  bool vertex_lists = false;                  // the vertex element holds a list property
  std::vector<uint8_t> buffer;
  // The faces' read-ahead (read_faces' common layout): bytes [at, end) not parsed yet.
  std::vector<uint8_t> ahead;
  size_t at = 0, end = 0;
  // ranged(): where the vertex and face records start in the file.
  bool ranged = false;
  uint64_t vertex_start = 0, face_start = 0;
};

namespace {

// The faces' common layout: the corner list alone, a 1-byte count, 4-byte integer indices
// (read_faces parses it from its read-ahead; a file of such triangles reads in ranges).
bool common_face_layout(const Element& f) {
  if (f.props.size() != 1) return false;
  const Property& only = f.props.front();
  return only.is_list && (only.name == "vertex_indices" || only.name == "vertex_index") && type_size(only.count) == 1 &&
         type_size(only.type) == 4 && only.type != PlyType::Float32;
}
}

PlyStream::PlyStream(const std::string& path) : path_(path), layout_(std::make_unique<Layout>()) {
  gz_ = gzopen(path.c_str(), "rb");
  if (!gz_) throw Error(path + ": cannot open");
  gzbuffer(static_cast<gzFile>(gz_), 1 << 20);
  // A header refused here never reaches the destructor: the file is closed on the way out.
  try {
    read_header();
  } catch (...) {
    gzclose(static_cast<gzFile>(gz_));
    gz_ = nullptr;
    throw;
  }
}

void PlyStream::read_header() {
  const std::string& path = path_;
  auto fail = [&](const std::string& why) { throw Error(path + ": " + why); };
  // The header, line by line (at most 1 MB of it).
  std::string line, header;
  auto next_line = [&]() {
    line.clear();
    for (;;) {
      const int c = gzgetc(static_cast<gzFile>(gz_));
      if (c < 0) fail("the PLY header ends before end_header");
      if (c == '\n') break;
      line.push_back(char(c));
      if (header.size() + line.size() > (1 << 20)) fail("the PLY header is longer than 1 MB");
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    header += line + "\n";
    return line;
  };
  if (next_line() != "ply") fail("not a PLY file");
  Layout& L = *layout_;
  bool binary = false;
  for (;;) {
    std::istringstream in(next_line());
    std::string word;
    in >> word;
    if (word == "end_header") break;
    if (word == "format") {
      std::string f;
      in >> f;
      if (f == "binary_little_endian" || f == "binary_big_endian") {
        binary = true;
        const bool big_host = __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;
        L.swap = (f == "binary_big_endian") != big_host;
      }
    } else if (word == "element") {
      Element e;
      in >> e.name >> e.count;
      if (!in) fail("bad element line: " + line);
      L.elements.push_back(e);
    } else if (word == "property") {
      if (L.elements.empty()) fail("a property before any element");
      Property p;
      std::string t;
      in >> t;
      if (t == "list") {
        std::string ct, it;
        in >> ct >> it >> p.name;
        p.is_list = true;
        if (!type_from_name(ct, p.count) || !type_from_name(it, p.type) || p.count == PlyType::Float32 ||
            p.count == PlyType::Float64)
          fail("bad list property: " + line);
      } else {
        in >> p.name;
        if (!type_from_name(t, p.type)) fail("unknown property type: " + line);
      }
      L.elements.back().props.push_back(p);
    }
  }
  if (!binary) fail("not a binary PLY (the out-of-core path streams binary PLY only)");
  for (size_t e = 0; e < L.elements.size(); ++e) {
    if (L.elements[e].name == "vertex" && L.vertex == SIZE_MAX) L.vertex = e;
    if (L.elements[e].name == "face" && L.face == SIZE_MAX) L.face = e;
  }
  if (L.vertex == SIZE_MAX || L.face == SIZE_MAX) fail("a PLY needs a vertex and a face element");
  if (L.face < L.vertex) fail("the PLY's faces come before its vertices");
  const Element& v = L.elements[L.vertex];
  for (const Property& p : v.props) {
    if (p.is_list) {  // a list (skipped): records differ in size
      L.vertex_lists = true;
      continue;
    }
    for (int a = 0; a < 3; ++a)
      if (p.name == std::string(1, char('x' + a))) {
        L.xyz_offset[a] = L.vertex_bytes;
        L.xyz_type[a] = p.type;
        L.has_xyz[a] = true;
      }
    L.vertex_bytes += type_size(p.type);
  }
  for (int a = 0; a < 3; ++a)
    if (!L.has_xyz[a]) fail("the vertex element has no x, y and z");
  double_xyz_ = L.xyz_type[0] == PlyType::Float64 || L.xyz_type[1] == PlyType::Float64 ||
                L.xyz_type[2] == PlyType::Float64;
  bool indices = false;
  for (const Property& p : L.elements[L.face].props)
    indices |= p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index");
  if (!indices) fail("the face element has no vertex_indices list");
  vertices_ = v.count;
  faces_ = L.elements[L.face].count;
  if (vertices_ > UINT32_MAX) fail("more than 4294967295 vertices");
  find_ranges();
}

void PlyStream::find_ranges() {
  Layout& L = *layout_;
  gzFile gz = static_cast<gzFile>(gz_);
  const z_off_t header = gztell(gz);
  if (header < 0 || gzdirect(gz) != 1) return;  // compressed: no seeking but from the start
  auto fixed_size = [&](const Element& e, uint64_t& bytes) {
    bytes = 0;
    for (const Property& p : e.props) {
      if (p.is_list) return false;
      bytes += type_size(p.type);
    }
    return true;
  };
  // Every product and sum checked: a header's counts are the file's word, not its size.
  uint64_t at = uint64_t(header), after = 0, bytes = 0, part = 0;
  for (size_t e = 0; e < L.elements.size(); ++e) {
    const Element& el = L.elements[e];
    if (e == L.face) {
      if (!common_face_layout(el)) return;
      L.face_start = at;
      if (__builtin_mul_overflow(el.count, kPlyTriangleBytes, &part) || __builtin_add_overflow(at, part, &at)) return;
      continue;
    }
    if (!fixed_size(el, bytes)) return;
    if (e == L.vertex) L.vertex_start = at;
    if (__builtin_mul_overflow(el.count, bytes, &part)) return;
    if (__builtin_add_overflow(e > L.face ? after : at, part, e > L.face ? &after : &at)) return;
  }
  uint64_t total = 0;
  struct stat st;
  L.ranged = !__builtin_add_overflow(at, after, &total) && ::stat(path_.c_str(), &st) == 0 &&
             uint64_t(st.st_size) == total;
}

bool PlyStream::ranged() const { return layout_->ranged; }

bool PlyStream::positions_fit_float() const {
  for (const PlyType t : layout_->xyz_type)
    if (t == PlyType::Float64 || t == PlyType::Int32 || t == PlyType::UInt32) return false;
  return true;
}

void PlyStream::seek(uint64_t offset) {
  Layout& L = *layout_;
  if (!L.ranged) throw Error("internal: " + path_ + " does not read in ranges");
  if (gzseek(static_cast<gzFile>(gz_), z_off_t(offset), SEEK_SET) != z_off_t(offset))
    throw Error(path_ + ": cannot seek in the file");
  L.at = L.end = 0;  // the faces' read-ahead, if any, was of another place
}

void PlyStream::seek_vertex(uint64_t first) {
  Layout& L = *layout_;
  if (first > vertices_) throw Error("internal: a vertex beyond the file's");
  seek(L.vertex_start + first * L.vertex_bytes);
  L.next = L.vertex;
  vertices_read_ = first;
}

void PlyStream::seek_face(uint64_t first) {
  Layout& L = *layout_;
  if (first > faces_) throw Error("internal: a face beyond the file's");
  seek(L.face_start + first * kPlyTriangleBytes);
  L.next = L.face;
  vertices_read_ = vertices_;
  faces_read_ = first;
}

PlyStream::~PlyStream() {
  if (gz_) gzclose(static_cast<gzFile>(gz_));
}

bool PlyStream::readable(const std::string& path) {
  // A binary PLY by its first lines (gzip or not); its header's problems are the
  // constructor's errors, never a reason to read the file whole instead.
  gzFile gz = gzopen(path.c_str(), "rb");
  if (!gz) return false;
  char head[512] = {0};
  const int got = gzread(gz, head, sizeof head - 1);
  gzclose(gz);
  if (got <= 0) return false;
  const std::string text(head, size_t(got));
  if (text.rfind("ply\n", 0) != 0 && text.rfind("ply\r\n", 0) != 0) return false;
  const size_t format = text.find("\nformat ");
  return format != std::string::npos && text.compare(format + 8, 7, "binary_") == 0;
}

void PlyStream::read_exact(void* to, size_t n) {
  auto* p = static_cast<uint8_t*>(to);
  while (n > 0) {
    const unsigned part = unsigned(std::min<size_t>(n, 1u << 30));
    const int got = gzread(static_cast<gzFile>(gz_), p, part);
    if (got <= 0) ended();
    p += got;
    n -= size_t(got);
  }
}

void PlyStream::skip_element(size_t e) {
  const Element& el = layout_->elements[e];
  uint8_t b[8];
  for (uint64_t i = 0; i < el.count; ++i)
    for (const Property& p : el.props) {
      if (!p.is_list) {
        read_exact(b, type_size(p.type));
        continue;
      }
      read_exact(b, type_size(p.count));
      const double n = read_value(b, p.count, layout_->swap);
      if (n < 0) throw Error(path_ + ": a negative list length in element " + el.name);
      for (double k = 0; k < n; ++k) read_exact(b, type_size(p.type));
    }
}

size_t PlyStream::read_vertices(double* out, size_t max) {
  Layout& L = *layout_;
  while (L.next < L.vertex) skip_element(L.next++);
  const size_t n = size_t(std::min<uint64_t>(max, vertices_ - vertices_read_));
  if (n == 0) return 0;
  if (L.vertex_lists) {
    // Property by property: scalars into a record of their own layout, lists skipped.
    std::vector<uint8_t> record(L.vertex_bytes);
    uint8_t b[8];
    for (size_t i = 0; i < n; ++i) {
      size_t at = 0;
      for (const Property& p : L.elements[L.vertex].props) {
        if (!p.is_list) {
          read_exact(&record[at], type_size(p.type));
          at += type_size(p.type);
          continue;
        }
        read_exact(b, type_size(p.count));
        const double items = read_value(b, p.count, L.swap);
        if (items < 0) throw Error(path_ + ": a negative list length in the vertex element");
        for (double k = 0; k < items; ++k) read_exact(b, type_size(p.type));
      }
      for (int a = 0; a < 3; ++a) out[3 * i + a] = read_value(&record[L.xyz_offset[a]], L.xyz_type[a], L.swap);
    }
    vertices_read_ += n;
    if (vertices_read_ == vertices_) L.next = L.vertex + 1;
    return n;
  }
  L.buffer.resize(n * L.vertex_bytes);
  read_exact(L.buffer.data(), L.buffer.size());
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      out[3 * i + a] = read_value(&L.buffer[i * L.vertex_bytes + L.xyz_offset[a]], L.xyz_type[a], L.swap);
  vertices_read_ += n;
  if (vertices_read_ == vertices_) L.next = L.vertex + 1;
  return n;
}

void PlyStream::ended() const { throw Error(path_ + ": the file ends before its header's counts are read"); }

void PlyStream::check_corner_count(double n) const {
  const std::string problem = polygon_size_problem(n < 0 ? 0 : uint64_t(n));
  if (!problem.empty()) throw Error(path_ + ": face " + std::to_string(faces_read_) + ": " + problem);
}

uint32_t PlyStream::corner(double x) const {
  if (!(x >= 0 && x < double(vertices_)))
    throw Error(path_ + ": face " + std::to_string(faces_read_) + " uses vertex " + std::to_string(int64_t(x)) +
                " but the file has " + std::to_string(vertices_) + " vertices");
  return uint32_t(x);
}

// At least `n` unparsed bytes in the faces' read-ahead, read from the file 1 MB at a time;
// false where the file ends first.
bool PlyStream::ahead(size_t n) {
  Layout& L = *layout_;
  if (L.end - L.at >= n) return true;
  // (Nothing to move before the first read: memmove on the empty buffer's null data is UB.)
  if (L.end > L.at) std::memmove(L.ahead.data(), L.ahead.data() + L.at, L.end - L.at);
  L.end -= L.at;
  L.at = 0;
  L.ahead.resize(std::max<size_t>(L.ahead.size(), std::max<size_t>(n, 1 << 20)));
  while (L.end < n) {
    const int got = gzread(static_cast<gzFile>(gz_), L.ahead.data() + L.end, unsigned(L.ahead.size() - L.end));
    if (got < 0) throw Error(path_ + ": cannot read the file");
    if (got == 0) return false;
    L.end += size_t(got);
  }
  return true;
}

size_t PlyStream::read_faces(std::vector<uint32_t>& triangles, size_t max) {
  Layout& L = *layout_;
  if (vertices_read_ < vertices_) throw Error("internal: faces read before every vertex");
  while (L.next < L.face) skip_element(L.next++);
  const Element& f = L.elements[L.face];
  size_t done = 0;
  const Property& only = f.props.front();
  if (common_face_layout(f)) {
    // The common layout (the corner list alone, a 1-byte count, 4-byte integer indices):
    // parsed from the read-ahead, where the general loop below reads each face in two
    // calls into zlib. The same checks and messages.
    const bool signed_count = only.count == PlyType::Int8, signed_index = only.type == PlyType::Int32;
    uint32_t poly[256];
    for (; done < max && faces_read_ < faces_; ++done, ++faces_read_) {
      if (!ahead(1)) ended();
      const int c = signed_count ? int(int8_t(L.ahead[L.at])) : int(L.ahead[L.at]);
      check_corner_count(c);
      ++L.at;
      if (!ahead(4 * size_t(c))) ended();
      for (int k = 0; k < c; ++k) {
        uint32_t u;
        std::memcpy(&u, &L.ahead[L.at + 4 * size_t(k)], 4);
        if (L.swap) u = __builtin_bswap32(u);
        poly[k] = corner(signed_index ? double(int32_t(u)) : double(u));
      }
      L.at += 4 * size_t(c);
      append_fan(triangles, poly, size_t(c));
    }
    return done;
  }
  std::vector<uint32_t> poly;
  uint8_t b[8];
  for (; done < max && faces_read_ < faces_; ++done, ++faces_read_) {
    for (const Property& p : f.props) {
      if (!p.is_list) {
        read_exact(b, type_size(p.type));
        continue;
      }
      read_exact(b, type_size(p.count));
      const double n = read_value(b, p.count, L.swap);
      const bool corners = p.name == "vertex_indices" || p.name == "vertex_index";
      if (!corners) {
        for (double k = 0; k < n; ++k) read_exact(b, type_size(p.type));
        continue;
      }
      check_corner_count(n);
      poly.resize(size_t(n));
      L.buffer.resize(size_t(n) * type_size(p.type));
      read_exact(L.buffer.data(), L.buffer.size());
      for (size_t k = 0; k < poly.size(); ++k) {
        poly[k] = corner(read_value(&L.buffer[k * type_size(p.type)], p.type, L.swap));
      }
      append_fan(triangles, poly.data(), poly.size());
    }
  }
  return done;
}

}  // namespace meshsal
