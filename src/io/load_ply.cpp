// meshsal: PLY reader (ascii, binary_little_endian, binary_big_endian).
// Reads the `vertex` element's x,y,z (any numeric type) plus its other scalar properties
// (returned as float), the `face` element's `vertex_indices` / `vertex_index` list (any
// count / index types), and skips every other property and element. Binary bodies are
// read straight from the in-memory bytes with memcpy; ascii with std::from_chars.
// Header counts are checked against the file size before anything is allocated, and the
// body must hold exactly what the header announces.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/model_frame.h"
#include "core/parallel.h"
#include "io/mesh_io_internal.h"
#include "io/ply_types.h"
#include "io/read_observer.h"
#include "io/seam_twins.h"
#include "io/text_scan.h"

namespace meshsal {
namespace {

struct Property {
  std::string name;
  PlyType type = PlyType::Float32;  // the item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

enum class Format { Ascii, BinaryLE, BinaryBE };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  size_t body = 0;  // byte offset of the body
  size_t body_line = 0;  // lines before the body (for ascii error messages)
};

// Names end up in error messages: printable ASCII only.
bool printable(std::string_view s) {
  for (char c : s)
    if (static_cast<unsigned char>(c) < 33 || static_cast<unsigned char>(c) > 126) return false;
  return true;
}

Header parse_header(std::string_view bytes, const std::string& name) {
  TextScan scan(std::string_view(bytes.data(), std::min<size_t>(bytes.size(), 1 << 20)), name);
  auto fail = [&](const std::string& problem) -> Error {
    return Error(name + ": header line " + std::to_string(scan.line_no) + ": " + problem);
  };
  const bool bom = scan.skip_bom();
  std::string_view line;
  if (!scan.next_line(line) || strip_comment(line) != "ply")
    throw Error(name + ": not a PLY file (it does not start with 'ply')");
  // A header cut short (truncated file) would otherwise be reported as its last odd line.
  if (scan.text.find("end_header") == std::string_view::npos)
    throw Error(name + ": PLY header has no end_header line (garbled or truncated file)");
  Header h;
  bool have_format = false, done = false;
  while (!done && scan.next_line(line)) {
    std::string_view rest = line;
    std::string_view key = next_token(rest);
    if (key.empty() || key == "comment" || key == "obj_info") continue;
    if (key.substr(0, 10) == "end_header") {
      if (!have_format) throw fail("end_header before any 'format' line");
      // The body starts right after this line's line end: anything else on the line (the
      // body glued on by a missing newline), or no line end at all, would misplace it.
      if (key.size() > 10 || !next_token(rest).empty())
        throw fail("more text after end_header on its line (a missing newline?)");
      if (scan.line_end == 0)
        throw fail("end_header is not followed by a newline (truncated file or a broken writer)");
      if (h.format != Format::Ascii && scan.line_end == '\r')
        throw fail("binary PLY header with CR-only line ends: where the body starts is ambiguous");
      done = true;
    } else if (key == "format") {
      std::string_view f = next_token(rest);
      if (f == "ascii") h.format = Format::Ascii;
      else if (f == "binary_little_endian") h.format = Format::BinaryLE;
      else if (f == "binary_big_endian") h.format = Format::BinaryBE;
      else throw fail("unknown format " + quoted(f));
      // A text editor that added a byte-order mark has probably rewritten the binary body too.
      if (bom && h.format != Format::Ascii)
        throw Error(name + ": a UTF-8 byte-order mark in front of a binary PLY header (saved by a text "
                           "editor? its binary body is probably damaged too)");
      have_format = true;
    } else if (key == "element") {
      Element e;
      e.name = std::string(next_token(rest));
      std::string_view c = next_token(rest);
      if (e.name.empty() || !parse_number(c, e.count) || !printable(e.name))
        throw fail("bad element line " + quoted(line));
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) throw fail("property before any element");
      Property p;
      std::string_view t = next_token(rest);
      if (t == "list") {
        p.is_list = true;
        std::string_view ct = next_token(rest), it = next_token(rest);
        if (!type_from_name(ct, p.count_type) || !type_from_name(it, p.type))
          throw fail("bad list property " + quoted(line));
        if (p.count_type == PlyType::Float32 || p.count_type == PlyType::Float64)
          throw fail("list count type must be an integer type");
      } else if (!type_from_name(t, p.type)) {
        throw fail("unknown property type " + quoted(t));
      }
      p.name = std::string(next_token(rest));
      if (p.name.empty()) throw fail("property without a name");
      if (!printable(p.name)) throw fail("property name " + quoted(p.name) + " has unprintable characters");
      h.elements.back().props.push_back(std::move(p));
    } else {
      throw fail("unexpected header line " + quoted(line));
    }
  }
  if (!done) throw Error(name + ": PLY header has no end_header line (garbled or truncated file)");
  h.body = scan.pos;  // <= bytes.size(): next_line never moves past the end
  h.body_line = scan.line_no;
  return h;
}

constexpr bool host_big_endian() {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  return true;
#else
  return false;
#endif
}


// What the reader does with each property of the vertex / face elements.
enum Role : int8_t { Skip = -1, X = 0, Y = 1, Z = 2, Extra = 3, Indices = 4 };

struct Plan {
  std::vector<Role> roles;        // per property
  std::vector<float*> extra_out;  // per property: where an Extra value goes (advanced per vertex)
};

struct Reader {
  std::string_view bytes;
  const std::string& name;
  Mesh& mesh;
  uint64_t vertex_count = UINT64_MAX;  // known once the vertex element is seen

  [[noreturn]] void fail(const std::string& problem) { throw Error(name + ": " + problem); }

  // Appends the fan triangles of one polygon given its indices; `line` > 0 names the
  // ascii line in errors.
  void add_polygon(const int64_t* idx, uint64_t n, uint64_t face, size_t line) {
    auto bad = [&](const std::string& problem) {
      fail((line ? "line " + std::to_string(line) + ": " : std::string()) + "face " +
           std::to_string(face) + problem);
    };
    if (n < 3) bad(" has " + std::to_string(n) + " vertices (needs at least 3)");
    if (n > kMaxPolygonCorners)
      bad(" has " + std::to_string(n) + " vertices (" + std::to_string(kMaxPolygonCorners) +
          " is the most a polygon may have)");
    for (uint64_t i = 0; i < n; ++i)
      if (idx[i] < 0 || static_cast<uint64_t>(idx[i]) >= vertex_count ||
          static_cast<uint64_t>(idx[i]) > 0xFFFFFFFEull)
        bad(" uses vertex index " + std::to_string(idx[i]) +
            (vertex_count == UINT64_MAX ? std::string(", out of range")
                                        : ", out of range (" + std::to_string(vertex_count) + " vertices)"));
    append_fan(mesh.triangles, idx, n);
  }

  template <bool Swap>
  size_t read_binary(const Element& e, Plan& plan, size_t pos) {
    const char* data = bytes.data();
    const size_t end = bytes.size();
    std::vector<int64_t> poly;
    for (uint64_t k = 0; k < e.count; ++k) {
      for (size_t j = 0; j < e.props.size(); ++j) {
        const Property& p = e.props[j];
        const Role role = plan.roles[j];
        if (!p.is_list) {
          size_t n = type_size(p.type);
          if (end - pos < n) truncated(e, k);
          if (role >= X && role <= Z) {
            mesh.source_positions.push_back(read_value<Swap>(data + pos, p.type));
          } else if (role == Extra) {
            *plan.extra_out[j]++ = static_cast<float>(read_value<Swap>(data + pos, p.type));
          }
          pos += n;
          continue;
        }
        size_t cn = type_size(p.count_type);
        if (end - pos < cn) truncated(e, k);
        double c = read_value<Swap>(data + pos, p.count_type);
        pos += cn;
        if (c < 0) fail(e.name + " " + std::to_string(k) + " has a negative list length");
        uint64_t count = static_cast<uint64_t>(c);
        size_t in = type_size(p.type);
        if (count > (end - pos) / in) truncated(e, k);
        if (role == Indices) {
          poly.resize(count);
          for (uint64_t i = 0; i < count; ++i) {
            double v = read_value<Swap>(data + pos + i * in, p.type);
            if (!(std::fabs(v) < 9e18) || v != std::trunc(v))
              fail("face " + std::to_string(k) + " has a non-integer vertex index");
            poly[i] = static_cast<int64_t>(v);
          }
          add_polygon(poly.data(), count, k, 0);
        }
        pos += count * in;
      }
    }
    return pos;
  }

  // Every face a triangle (count 3, 13 bytes each, every index in range), the layout
  // meshsal and most tools write: copied on every core, each range from its own offset.
  // False (nothing added) when some face is not, for the one-at-a-time loop to read (and
  // to name a bad face as it does).
  bool read_triangles_parallel(const Element& e, const Property& p, size_t& pos) {
    if (e.count == 0 || e.count > (bytes.size() - pos) / 13) return false;
    const uint64_t limit = p.type == PlyType::Int32 ? std::min<uint64_t>(vertex_count, uint64_t(1) << 31) : vertex_count;
    const size_t old = mesh.triangles.size();
    mesh.triangles.resize(old + 3 * e.count);
    std::atomic<bool> plain{true};
    const char* first = bytes.data() + pos;
    parallel_for(e.count, 0, 1 << 16, [&](size_t begin, size_t end) {
      const char* in = first + 13 * begin;
      uint32_t* out = mesh.triangles.data() + old + 3 * begin;
      for (size_t k = begin; k < end; ++k, in += 13, out += 3) {
        uint32_t t[3];
        std::memcpy(t, in + 1, 12);
        if (in[0] != 3 || t[0] >= limit || t[1] >= limit || t[2] >= limit) {
          plain.store(false, std::memory_order_relaxed);
          return;
        }
        out[0] = t[0], out[1] = t[1], out[2] = t[2];
      }
    });
    if (!plain.load()) {
      mesh.triangles.resize(old);
      return false;
    }
    pos += 13 * e.count;
    return true;
  }

  // Fast path for the common face layout: only the index list, uchar/char count and
  // 32-bit indices in host byte order. Returns false when the element does not qualify.
  bool read_faces_fast(const Element& e, const Plan& plan, size_t& pos, bool swap) {
    if (swap || e.props.size() != 1 || plan.roles[0] != Indices) return false;
    const Property& p = e.props[0];
    if (type_size(p.count_type) != 1 || type_size(p.type) != 4 || p.type == PlyType::Float32) return false;
    if (vertex_count == UINT64_MAX) return false;  // faces before vertices: use the slow path
    const bool signed_count = p.count_type == PlyType::Int8;
    const char* data = bytes.data();
    const size_t end = bytes.size();
    if (read_triangles_parallel(e, p, pos)) return true;
    int64_t poly[256];
    for (uint64_t k = 0; k < e.count; ++k) {
      if (pos >= end) truncated(e, k);
      int c = signed_count ? static_cast<int8_t>(data[pos]) : static_cast<uint8_t>(data[pos]);
      if (c < 0) fail(e.name + " " + std::to_string(k) + " has a negative list length");
      ++pos;
      if (static_cast<size_t>(c) * 4 > end - pos) truncated(e, k);
      if (c == 3) {
        uint32_t t[3];
        std::memcpy(t, data + pos, 12);
        if (p.type == PlyType::UInt32 ? (t[0] < vertex_count && t[1] < vertex_count && t[2] < vertex_count)
                                      : (int32_t(t[0]) >= 0 && int32_t(t[1]) >= 0 && int32_t(t[2]) >= 0 &&
                                         t[0] < vertex_count && t[1] < vertex_count && t[2] < vertex_count)) {
          mesh.triangles.insert(mesh.triangles.end(), t, t + 3);
          pos += 12;
          continue;
        }
      }
      for (int i = 0; i < c; ++i) {
        uint32_t u;
        std::memcpy(&u, data + pos + 4 * i, 4);
        poly[i] = p.type == PlyType::UInt32 ? int64_t(u) : int64_t(int32_t(u));
      }
      add_polygon(poly, static_cast<uint64_t>(c), k, 0);
      pos += 4 * size_t(c);
    }
    return true;
  }

  // Fast path for a vertex element without lists: fixed stride, one bounds check.
  template <bool Swap>
  bool read_fixed_fast(const Element& e, Plan& plan, size_t& pos) {
    size_t stride = 0;
    for (const Property& p : e.props) {
      if (p.is_list) return false;
      stride += type_size(p.type);
    }
    if (e.count > (bytes.size() - pos) / stride) truncated(e, (bytes.size() - pos) / stride);
    std::vector<size_t> offset(e.props.size());
    for (size_t j = 0, o = 0; j < e.props.size(); o += type_size(e.props[j].type), ++j) offset[j] = o;
    const char* base = bytes.data() + pos;
    // x, y, z as adjacent host-order floats: one 12-byte copy per vertex.
    const bool packed_xyz = !Swap && plan.roles.size() >= 3 && plan.roles[0] == X && plan.roles[1] == Y &&
                            plan.roles[2] == Z && e.props[0].type == PlyType::Float32 &&
                            e.props[1].type == PlyType::Float32 && e.props[2].type == PlyType::Float32;
    const size_t first = packed_xyz ? 3 : 0;
    const size_t old = mesh.source_positions.size();
    mesh.source_positions.resize(old + 3 * e.count);
    // Every vertex at its own offset: ranges of them on every core.
    parallel_for(e.count, 0, 1 << 16, [&](size_t begin, size_t end) {
      const char* in = base + begin * stride;
      double* out = mesh.source_positions.data() + old + 3 * begin;
      for (size_t k = begin; k < end; ++k, in += stride, out += 3) {
        if (packed_xyz) {
          float xyz[3];
          std::memcpy(xyz, in, 12);
          for (int c = 0; c < 3; ++c) out[c] = xyz[c];
        }
        for (size_t j = first; j < e.props.size(); ++j) {
          const Role role = plan.roles[j];
          if (role == Skip) continue;
          const double v = read_value<Swap>(in + offset[j], e.props[j].type);
          if (role == Extra) plan.extra_out[j][k] = static_cast<float>(v);
          else out[role] = v;
        }
      }
    });
    for (size_t j = 0; j < e.props.size(); ++j)
      if (plan.roles[j] == Extra) plan.extra_out[j] += e.count;
    pos += e.count * stride;
    return true;
  }

  [[noreturn]] void truncated(const Element& e, uint64_t k) {
    fail("truncated: the file ends inside " + e.name + " " + std::to_string(k) + " of " +
         std::to_string(e.count));
  }

  size_t read_ascii(const Element& e, Plan& plan, TextScan& scan) {
    std::string_view line;
    std::vector<int64_t> poly;
    auto fail_line = [&](const std::string& problem) {
      fail("line " + std::to_string(scan.line_no) + ": " + problem);
    };
    for (uint64_t k = 0; k < e.count; ++k) {
      do {
        if (!scan.next_line(line))
          fail("truncated: the header says " + std::to_string(e.count) + " " + e.name +
               " elements but the file ends after " + std::to_string(k));
      } while (strip_comment(line).empty());
      if (std::string_view peek = line; next_token(peek) == "comment")
        fail_line("a 'comment' line inside the body (PLY allows comments only in the header)");
      for (size_t j = 0; j < e.props.size(); ++j) {
        const Property& p = e.props[j];
        const Role role = plan.roles[j];
        std::string_view tok = next_token(line);
        if (tok.empty())
          fail_line(e.name + " " + std::to_string(k) + " has fewer values than the header declares");
        if (!p.is_list) {
          if (role == Extra) {
            float v;
            if (!parse_coord(tok, v)) fail_line("bad number " + quoted(tok));
            *plan.extra_out[j]++ = v;
          } else if (role >= X && role <= Z) {
            double v;
            if (!parse_coord(tok, v)) fail_line("bad number " + quoted(tok));
            mesh.source_positions.push_back(v);
          }
          continue;
        }
        uint64_t count;
        if (!parse_number(tok, count)) fail_line("bad list length " + quoted(tok));
        if (count > line.size()) fail_line("list length " + std::to_string(count) + " is longer than the line");
        poly.resize(count);
        for (uint64_t i = 0; i < count; ++i) {
          tok = next_token(line);
          if (tok.empty()) fail_line("list has fewer than its " + std::to_string(count) + " values");
          if (role == Indices && !parse_number(tok, poly[i])) fail_line("bad vertex index " + quoted(tok));
        }
        if (role == Indices) add_polygon(poly.data(), count, k, scan.line_no);
      }
      if (!next_token(line).empty())
        fail_line(e.name + " " + std::to_string(k) + " has more values than the header declares");
    }
    return scan.pos;
  }
};

// Bytes the body needs for the header's counts: fixed-size values, list counts and
// `list_items` items per list (binary), or 2 bytes per value ("0 ") in ascii.
unsigned __int128 body_bytes_needed(const Header& h, unsigned list_items) {
  const bool ascii = h.format == Format::Ascii;
  unsigned __int128 total = 0;
  for (const Element& e : h.elements) {
    uint64_t size = 0;
    for (const Property& p : e.props)
      size += ascii ? 2 * (1 + (p.is_list ? list_items : 0))
                    : type_size(p.is_list ? p.count_type : p.type) + (p.is_list ? list_items * type_size(p.type) : 0);
    total += static_cast<unsigned __int128>(size) * e.count;
  }
  return total;
}

}  // namespace

uint64_t ply_input_limit(std::string_view head, const std::string& name) {
  const Header h = parse_header(head, name);
  return counts_limit(h.body, body_bytes_needed(h, 3));
}

namespace {

// Refuses counts the body cannot possibly hold, before anything is allocated: a binary
// element needs at least the sum of its fixed-size parts, an ascii one 2 bytes per value.
void check_counts_fit(const Header& h, size_t body_size, const std::string& name) {
  const unsigned __int128 min_total = body_bytes_needed(h, 0);
  if (min_total > body_size)
    throw Error(name + ": header element counts need at least " +
                std::to_string(static_cast<uint64_t>(std::min<unsigned __int128>(min_total, UINT64_MAX))) +
                " bytes but the body has " + std::to_string(body_size) +
                " (truncated file or bad header)");
}

// What to do with each property of each element, and where extra vertex properties go.
struct ElementPlans {
  std::vector<Plan> plans;                 // per element
  std::vector<std::vector<float>> extras;  // storage while reading, moved out at the end
  std::vector<std::string> extra_names;
  // What no reading keeps (vertex list properties, face properties besides the indices,
  // other elements), for LoadReport::unread.
  std::vector<std::string> unread;
};

ElementPlans plan_elements(const Header& h, const Element* vertex, const Element* face,
                           size_t body_size, bool want_properties, Mesh& mesh,
                           const std::string& name) {
  const bool ascii = h.format == Format::Ascii;
  ElementPlans out;
  bool face_list_found = false;
  out.plans.resize(h.elements.size());
  for (size_t ei = 0; ei < h.elements.size(); ++ei) {
    const Element& e = h.elements[ei];
    Plan& plan = out.plans[ei];
    plan.roles.assign(e.props.size(), Skip);
    plan.extra_out.assign(e.props.size(), nullptr);
    if (&e == vertex) {
      int found[3] = {-1, -1, -1};
      for (size_t j = 0; j < e.props.size(); ++j) {
        const Property& p = e.props[j];
        if (p.is_list) {
          out.unread.push_back("vertex list property '" + p.name + "'");
          continue;
        }
        int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
        if (axis >= 0 && found[axis] < 0) {
          found[axis] = static_cast<int>(j);
          plan.roles[j] = static_cast<Role>(axis);
          mesh.double_positions |= p.type == PlyType::Float64;  // written back as double
        } else if (want_properties) {
          plan.roles[j] = Extra;
          out.extras.emplace_back(e.count);
          out.extra_names.push_back(p.name);
        }
      }
      if (found[0] < 0 || found[1] < 0 || found[2] < 0)
        throw Error(name + ": the vertex element lacks an x, y or z property");
      // Positions are pushed in property order; x,y,z must therefore be in that order.
      if (!(found[0] < found[1] && found[1] < found[2]))
        throw Error(name + ": vertex properties x, y, z are not in x, y, z order");
      size_t n = 0;
      for (size_t j = 0; j < e.props.size(); ++j)
        if (plan.roles[j] == Extra) plan.extra_out[j] = out.extras[n++].data();
      mesh.source_positions.reserve(e.count * 3);
    } else if (&e == face) {
      uint64_t min_face_bytes = 8;  // ascii "3 0 1 2\n"
      for (size_t j = 0; j < e.props.size(); ++j)
        if (e.props[j].is_list && !face_list_found &&
            (e.props[j].name == "vertex_indices" || e.props[j].name == "vertex_index")) {
          plan.roles[j] = Indices;
          face_list_found = true;
          if (!ascii) min_face_bytes = type_size(e.props[j].count_type) + 3 * type_size(e.props[j].type);
        }
      if (!face_list_found)
        throw Error(name + ": the face element has no vertex_indices list");
      for (size_t j = 0; j < e.props.size(); ++j)
        if (plan.roles[j] != Indices) out.unread.push_back("face property '" + e.props[j].name + "'");
      // As many triangles as the body can hold, not as the header claims: a face needs a
      // count and 3 indices (a header of 1-byte faces must not reserve 12 bytes for each).
      mesh.triangles.reserve(std::min<uint64_t>(e.count, body_size / min_face_bytes) * 3);
    } else {
      out.unread.push_back("element '" + e.name + "'");
    }
  }
  return out;
}

// Reads every element in header order; returns where the body ended. `vertices_read` is
// called once the vertex element is.
size_t read_body(Reader& reader, const Header& h, std::vector<Plan>& plans, const Element* vertex,
                 const std::function<void()>& vertices_read) {
  if (h.format == Format::Ascii) {
    TextScan scan(reader.bytes, reader.name);
    scan.pos = h.body;
    scan.line_no = h.body_line;
    for (size_t ei = 0; ei < h.elements.size(); ++ei) {
      if (h.elements[ei].props.empty()) continue;
      reader.read_ascii(h.elements[ei], plans[ei], scan);
      if (&h.elements[ei] == vertex) {
        reader.vertex_count = vertex->count;
        vertices_read();
      }
    }
    return scan.pos;
  }
  const bool swap = (h.format == Format::BinaryBE) != host_big_endian();
  size_t end = h.body;
  for (size_t ei = 0; ei < h.elements.size(); ++ei) {
    if (h.elements[ei].props.empty()) continue;
    const Element& e = h.elements[ei];
    if (reader.read_faces_fast(e, plans[ei], end, swap)) continue;
    if (&e == vertex && (swap ? reader.read_fixed_fast<true>(e, plans[ei], end)
                              : reader.read_fixed_fast<false>(e, plans[ei], end))) {
      reader.vertex_count = vertex->count;
      vertices_read();
      continue;
    }
    end = swap ? reader.read_binary<true>(e, plans[ei], end) : reader.read_binary<false>(e, plans[ei], end);
    if (&h.elements[ei] == vertex) {
      reader.vertex_count = vertex->count;
      vertices_read();
    }
  }
  return end;
}

// The body must end where the header says (blank space aside).
void check_nothing_after(std::string_view bytes, size_t end, bool ascii, const std::string& name) {
  if (ascii) {
    TextScan rest(bytes, name);
    rest.pos = std::min(end, bytes.size());
    std::string_view line;
    while (rest.next_line(line))
      if (next_token(line) == "comment")
        throw Error(name + ": a 'comment' line after the last element (PLY allows comments only in the header)");
  }
  for (size_t i = std::min(end, bytes.size()); i < bytes.size(); ++i)
    if (!is_space(bytes[i]) && bytes[i] != '\n')
      throw Error(name + ": " + std::to_string(bytes.size() - end) +
                  " bytes of data after the last element: the header counts disagree with the body");
}

}  // namespace

Mesh load_ply_bytes(std::string_view bytes, const std::string& name, VertexProperties* properties,
                    bool attributes, std::vector<std::string>* unread, std::vector<std::string>* not_read,
                    ReadObserver* observer) {
  const Header h = parse_header(bytes, name);
  const size_t body_size = bytes.size() - std::min(h.body, bytes.size());
  check_counts_fit(h, body_size, name);
  const Element* vertex = nullptr;
  const Element* face = nullptr;
  for (const Element& e : h.elements) {
    if (e.name == "vertex" && !vertex) vertex = &e;
    if (e.name == "face" && !face) face = &e;
  }
  if (!vertex) throw Error(name + ": PLY has no 'vertex' element");
  if (vertex->count > 0xFFFFFFFFull) throw Error(name + ": too many vertices");

  Mesh mesh;
  // The other scalar properties are read even when they are not kept: a UV seam is told
  // from a plain duplicate by them (find_seam_twins below).
  ElementPlans plan = plan_elements(h, vertex, face, body_size, true, mesh, name);
  if (!face) {
    bool strips = false;
    for (const Element& e : h.elements) strips |= e.name == "tristrips";
    throw Error(name + (strips ? ": PLY stores triangle strips (tristrips), which are not supported"
                               : ": PLY has no 'face' element (a point cloud, not a mesh)"));
  }
  // The observer is told of the positions once the vertices are read (made early: their
  // origin is nearly always the final one), and of the triangles once the faces are; it
  // is ended before the mesh is dropped by a throw, or its positions made again (the
  // load's caller ends it as it returns the mesh).
  const EndObserver end_on_throw(observer, true);
  EarlyPositions early;
  const auto vertices_read = [&] {
    if (!observer) return;
    early = early_model_positions(mesh, mesh.source_positions.data(), mesh.source_positions.size() / 3);
    observer->positions_read(mesh.positions.data(), early.vertex_count);
  };
  Reader reader{bytes, name, mesh};
  const size_t end = read_body(reader, h, plan.plans, vertex, vertices_read);
  check_nothing_after(bytes, end, h.format == Format::Ascii, name);
  // The origin, from the mesh points' box. Where the positions told were made at another
  // (a vertex no triangle uses lies outside that box), the observer is ended before they
  // are made again, and told nothing more.
  const size_t nv = mesh.source_positions.size() / 3;
  double origin[3];
  model_origin(mesh, mesh.source_positions.data(), nv, origin);
  const bool kept = observer && keeps_early_positions(early, nv, origin);
  if (observer && !kept) observer->read_ended(false);
  else if (observer) observer->triangles_read(mesh.triangles.data(), mesh.triangle_count());
  if (unread) *unread = std::move(plan.unread);
  for (size_t i = 0; i < plan.extras.size(); ++i) {
    if (properties) (*properties)[plan.extra_names[i]] = plan.extras[i];
    mesh.attributes.push_back({plan.extra_names[i], std::move(plan.extras[i])});
  }
  set_model_positions_at(mesh, mesh.source_positions.data(), nv, origin, kept ? &early : nullptr);
  // A PLY stores a UV seam as vertices split at one position: found here, with or without
  // the attributes kept, so that saliency and simplification see one surface there, as for
  // an OBJ's v/vt corners (every front end reads a PLY so).
  find_seam_twins(mesh);
  // Such a mesh is computed on its welded twin, whose arrays are others: the observer's
  // work would be wasted.
  if (kept && !mesh.position_vertex.empty()) observer->read_ended(false);
  if (!attributes) {
    for (const VertexAttribute& a : mesh.attributes) note_not_read(not_read, a.name);
    std::vector<VertexAttribute>().swap(mesh.attributes);
  }
  return mesh;
}

}  // namespace meshsal
