// meshsal: STL reader, ASCII and binary. STL stores each triangle's three corners by value,
// so corners at identical positions are welded into shared vertices (curvature needs the
// connectivity). Binary or ASCII is decided by the size check 84 + 50 n: binary files whose
// 80-byte header starts with "solid" exist.
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <unordered_map>

#include "io/mesh_io_internal.h"
#include "io/text_scan.h"

namespace meshsal {
namespace {

constexpr uint64_t kBinaryHeaderBytes = 84;  // 80-byte header + uint32 triangle count
constexpr uint64_t kBinaryFacetBytes = 50;   // normal, 3 corners (12 floats), uint16 attribute

uint32_t read_u32_le(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}

float read_f32_le(const char* p) {
  const uint32_t bits = read_u32_le(p);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

// "solid" as the first word (after a byte-order mark and blanks).
bool starts_with_solid(std::string_view bytes) {
  if (bytes.substr(0, 3) == TextScan::kBom) bytes.remove_prefix(3);
  while (!bytes.empty() && (is_space(bytes.front()) || bytes.front() == '\n')) bytes.remove_prefix(1);
  return bytes.substr(0, 5) == "solid" && (bytes.size() == 5 || is_space(bytes[5]) || bytes[5] == '\n');
}

bool is_binary_size(std::string_view bytes) {
  return bytes.size() >= kBinaryHeaderBytes &&
         kBinaryHeaderBytes + kBinaryFacetBytes * uint64_t(read_u32_le(bytes.data() + 80)) == bytes.size();
}

// Corners (x,y,z per corner, 3 corners per triangle) to a welded mesh: one vertex per
// distinct position, in order of first appearance. Exact float equality (-0 equals +0).
Mesh weld(const std::vector<float>& corners, uint64_t* welded) {
  struct Key {
    uint32_t b[3];
    bool operator==(const Key& o) const { return b[0] == o.b[0] && b[1] == o.b[1] && b[2] == o.b[2]; }
  };
  struct Hash {
    size_t operator()(const Key& k) const {
      uint64_t h = k.b[0] * 0x9E3779B97F4A7C15ull;
      h = (h ^ (h >> 29) ^ k.b[1]) * 0xBF58476D1CE4E5B9ull;
      h = (h ^ (h >> 31) ^ k.b[2]) * 0x94D049BB133111EBull;
      return static_cast<size_t>(h ^ (h >> 32));
    }
  };
  const size_t n = corners.size() / 3;
  std::unordered_map<Key, uint32_t, Hash> index;
  index.reserve(n);
  Mesh mesh;
  mesh.triangles.reserve(n);
  for (size_t c = 0; c < n; ++c) {
    Key key;
    for (int k = 0; k < 3; ++k) key.b[k] = position_bits(corners[3 * c + k]);
    auto [it, fresh] = index.emplace(key, static_cast<uint32_t>(mesh.source_positions.size() / 3));
    if (fresh) mesh.source_positions.insert(mesh.source_positions.end(), &corners[3 * c], &corners[3 * c] + 3);
    mesh.triangles.push_back(it->second);
  }
  if (welded) *welded = n - mesh.source_positions.size() / 3;
  localize_read_positions(mesh);
  return mesh;
}

// A NaN would never equal itself and so never weld: refused here, naming the facet.
void check_finite(const std::vector<float>& corners, const std::string& name) {
  for (size_t i = 0; i < corners.size(); ++i)
    if (!std::isfinite(corners[i]))
      throw Error(name + ": facet " + std::to_string(i / 9) + " has a non-finite coordinate");
}

std::vector<float> binary_corners(std::string_view bytes, const std::string& name) {
  if (bytes.size() < kBinaryHeaderBytes)
    throw Error(name + ": not an STL file (" + std::to_string(bytes.size()) +
                " bytes: shorter than a binary STL header, and it does not start with 'solid')");
  const uint64_t n = read_u32_le(bytes.data() + 80);
  const uint64_t need = kBinaryHeaderBytes + kBinaryFacetBytes * n;
  if (need != bytes.size())
    throw Error(name + ": binary STL: the header says " + std::to_string(n) + " triangles (" +
                std::to_string(need) + " bytes) but the file has " + std::to_string(bytes.size()) +
                " bytes" + (need > bytes.size() ? " (truncated?)" : ""));
  std::vector<float> corners(9 * n);
  for (uint64_t t = 0; t < n; ++t) {
    const char* p = bytes.data() + kBinaryHeaderBytes + kBinaryFacetBytes * t + 12;  // skip the normal
    for (int k = 0; k < 9; ++k) corners[9 * t + k] = read_f32_le(p + 4 * k);
  }
  return corners;
}

// ASCII: solid NAME / facet normal x y z / outer loop / vertex x y z (x3) / endloop /
// endfacet ... endsolid NAME. Several solids in one file are read as one mesh. Keywords
// are matched as tokens, so line breaks inside a facet do not matter; the normal is ignored.
struct AsciiReader {
  TextScan scan;
  std::string_view line;
  explicit AsciiReader(std::string_view text, const std::string& name) : scan(text, name) {}

  Error fail(const std::string& problem) const {
    return Error(scan.name + ": line " + std::to_string(scan.line_no) + ": " + problem);
  }
  // The next token, crossing line ends; empty at the end of the file.
  std::string_view token() {
    for (;;) {
      std::string_view t = next_token(line);
      if (!t.empty()) return t;
      if (!scan.next_line(line)) return {};
    }
  }
  void expect(std::string_view word) {
    const std::string_view t = token();
    if (t.empty()) throw Error(scan.name + ": truncated: the file ends where '" + std::string(word) + "' was expected");
    if (t != word) throw fail("expected '" + std::string(word) + "', found " + quoted(t));
  }
  void number(std::vector<float>* out) {
    const std::string_view t = token();
    if (t.empty()) throw Error(scan.name + ": truncated: the file ends inside a facet");
    float x;
    if (!parse_coord(t, x)) throw fail("bad coordinate " + quoted(t));
    if (out) out->push_back(x);
  }

  std::vector<float> read() {
    std::vector<float> corners;
    scan.skip_bom();
    bool in_solid = false;
    for (;;) {
      const std::string_view t = token();
      if (t.empty()) {
        if (in_solid) throw Error(scan.name + ": truncated: the file ends without 'endsolid'");
        break;
      }
      if (!in_solid) {
        if (t != "solid") throw fail("expected 'solid', found " + quoted(t));
        line = {};  // the rest of the line is the solid's name
        in_solid = true;
      } else if (t == "endsolid") {
        line = {};
        in_solid = false;
      } else if (t == "facet") {
        expect("normal");
        for (int k = 0; k < 3; ++k) number(nullptr);
        expect("outer");
        expect("loop");
        for (int c = 0; c < 3; ++c) {
          expect("vertex");
          for (int k = 0; k < 3; ++k) number(&corners);
        }
        expect("endloop");
        expect("endfacet");
      } else {
        throw fail("expected 'facet' or 'endsolid', found " + quoted(t));
      }
    }
    return corners;
  }
};

}  // namespace

uint64_t stl_input_limit(std::string_view head, const std::string& name) {
  (void)name;
  // ASCII has no counts; a binary header's count bounds the size (checked exactly later).
  if (starts_with_solid(head) || head.size() < kBinaryHeaderBytes) return kNoHeaderLimitBytes;
  return counts_limit(kBinaryHeaderBytes, static_cast<unsigned __int128>(read_u32_le(head.data() + 80)) *
                                              kBinaryFacetBytes);
}

Mesh load_stl_bytes(std::string_view bytes, const std::string& name, uint64_t* welded) {
  // ASCII never holds a NUL byte: a "solid" file with one is a binary STL of the wrong size.
  const bool binary = is_binary_size(bytes) || !starts_with_solid(bytes) ||
                      bytes.find('\0') != std::string_view::npos;
  std::vector<float> corners = binary ? binary_corners(bytes, name) : AsciiReader(bytes, name).read();
  if (corners.empty()) throw Error(name + ": STL file has no facets");
  if (corners.size() / 3 > 0xFFFFFFFFull) throw Error(name + ": more STL corners than 32-bit indices hold");
  check_finite(corners, name);
  return weld(corners, welded);
}

}  // namespace meshsal
