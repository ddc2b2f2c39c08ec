// meshsal: OFF reader. Accepts the OFF / COFF / NOFF / CNOFF / STOFF... header keywords,
// '#' comments, counts on the header line or the next, and optional colour columns after a
// face's indices. One vertex or face per line, as every OFF writer does. With attributes,
// the vertex columns the keyword announces are kept (x y z [nx ny nz] [r g b [a]] [s t], in
// the order of the OFF format): normals, colours (integers 0..255, or numbers in [0, 1]
// when any has a point or exponent) and texture coordinates.
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "io/mesh_io_internal.h"
#include "io/text_scan.h"

namespace meshsal {

namespace {

// Next non-empty line after comments are stripped; false at the end.
bool content_line(TextScan& scan, std::string_view& out) {
  while (scan.next_line(out)) {
    out = strip_comment(out);
    if (!out.empty()) return true;
  }
  return false;
}

Error line_error(const TextScan& scan, const std::string& problem) {
  return Error(scan.name + ": line " + std::to_string(scan.line_no) + ": " + problem);
}

// The vertex columns a keyword announces (its letters before "OFF").
struct OffColumns {
  bool normals = false, colours = false, texcoords = false;
};

// Reads the keyword and the vertex / face counts; leaves `scan` after the counts line.
void parse_off_header(TextScan& scan, uint64_t counts[2], OffColumns* columns = nullptr) {
  std::string_view line;
  scan.skip_bom();
  if (!content_line(scan, line)) throw Error(scan.name + ": empty file");
  std::string_view keyword = next_token(line);
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF")
    throw line_error(scan, "not an OFF file (the first word is " + quoted(keyword) + ", expected OFF)");
  for (char c : keyword.substr(0, keyword.size() - 3))
    if (c != 'C' && c != 'N' && c != 'S' && c != 'T')
      throw line_error(scan, "unsupported OFF variant " + quoted(keyword));
  if (columns) {
    const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
    columns->normals = prefix.find('N') != std::string_view::npos;
    columns->colours = prefix.find('C') != std::string_view::npos;
    columns->texcoords = prefix.find("ST") != std::string_view::npos;
  }
  if (line.find_first_not_of(" \t") != std::string_view::npos) {
    std::string_view peek = line;
    if (next_token(peek) == "BINARY") throw line_error(scan, "binary OFF is not supported");
  } else if (!content_line(scan, line)) {
    throw line_error(scan, "missing the vertex / face / edge counts");
  }
  for (int k = 0; k < 2; ++k) {
    std::string_view tok = next_token(line);
    if (!parse_number(tok, counts[k])) throw line_error(scan, "bad count " + quoted(tok) + " in the header");
  }
}

// The extra vertex columns as read, in file order.
struct OffExtra {
  std::vector<float> normals, colours, texcoords;  // 3, 4 and 2 per vertex
  bool float_colours = false;                      // a colour written as a fraction of 1
};

// Takes the columns after x y z of one vertex line. A colour has 3 or 4 numbers: 4 when the
// line holds that many before its texture coordinates (alpha 255, or 1, otherwise).
std::string take_off_columns(std::string_view& line, const OffColumns& columns, OffExtra& extra) {
  std::vector<std::string_view> tokens;
  for (std::string_view tok = next_token(line); !tok.empty(); tok = next_token(line)) tokens.push_back(tok);
  size_t at = 0;
  auto take = [&](size_t n, std::vector<float>& out, const char* what) -> std::string {
    for (size_t k = 0; k < n; ++k, ++at) {
      float x;
      if (at >= tokens.size()) return std::string("vertex needs its ") + what;
      if (!parse_coord(tokens[at], x) || !std::isfinite(x)) return std::string("bad ") + what + " " + quoted(tokens[at]);
      out.push_back(x);
    }
    return "";
  };
  if (columns.normals)
    if (std::string p = take(3, extra.normals, "normal"); !p.empty()) return p;
  if (columns.colours) {
    const size_t left = tokens.size() - std::min(tokens.size(), at) - (columns.texcoords ? 2 : 0);
    const size_t n = left >= 4 ? 4 : 3;
    for (size_t k = at; k < at + n && k < tokens.size(); ++k)
      if (tokens[k].find_first_of(".eE") != std::string_view::npos) extra.float_colours = true;
    if (std::string p = take(n, extra.colours, "colour"); !p.empty()) return p;
    if (n == 3) extra.colours.push_back(-1);  // no alpha: opaque, whatever the scale
  }
  if (columns.texcoords)
    if (std::string p = take(2, extra.texcoords, "texture coordinate"); !p.empty()) return p;
  return "";
}

// The columns as the attributes every format shares: nx ny nz, red green blue alpha (bytes
// 0..255), u v.
void add_off_attributes(Mesh& mesh, const OffColumns& columns, OffExtra extra) {
  const size_t n = mesh.source_positions.size() / 3;
  auto add = [&](const char* name, const std::vector<float>& values, size_t stride, size_t k, auto convert) {
    VertexAttribute a{name, std::vector<float>(n)};
    for (size_t v = 0; v < n; ++v) a.values[v] = convert(values[stride * v + k]);
    mesh.attributes.push_back(std::move(a));
  };
  const auto same = [](float x) { return x; };
  if (columns.normals)
    for (size_t k = 0; k < 3; ++k) add(k == 0 ? "nx" : k == 1 ? "ny" : "nz", extra.normals, 3, k, same);
  if (columns.colours) {
    const double scale = extra.float_colours ? 255.0 : 1.0;
    const auto byte = [&](float x) { return x < 0 ? 255.0f : float(std::clamp(std::nearbyint(x * scale), 0.0, 255.0)); };
    for (size_t k = 0; k < 4; ++k) add(k == 0 ? "red" : k == 1 ? "green" : k == 2 ? "blue" : "alpha", extra.colours, 4, k, byte);
  }
  if (columns.texcoords)
    for (size_t k = 0; k < 2; ++k) add(k == 0 ? "u" : "v", extra.texcoords, 2, k, same);
}

// Every vertex takes at least 6 bytes ("0 0 0\n") and every face 8 ("3 0 1 2\n").
constexpr uint64_t kMinVertexBytes = 6, kMinFaceBytes = 8;

}  // namespace

uint64_t off_input_limit(std::string_view head, const std::string& name) {
  TextScan scan(head, name);
  uint64_t counts[2];
  parse_off_header(scan, counts);
  return counts_limit(scan.pos, static_cast<unsigned __int128>(counts[0]) * kMinVertexBytes +
                                    static_cast<unsigned __int128>(counts[1]) * kMinFaceBytes);
}

Mesh load_off_text(std::string_view text, const std::string& name, bool attributes, std::vector<std::string>* not_read) {
  TextScan scan(text, name);
  std::string_view line;
  auto fail = [&](const std::string& problem) { return line_error(scan, problem); };
  uint64_t counts[2];
  OffColumns columns;
  parse_off_header(scan, counts, &columns);
  if (!attributes) {
    if (columns.normals) note_not_read(not_read, "nx");
    if (columns.colours) note_not_read(not_read, "red");
    if (columns.texcoords) note_not_read(not_read, "u");
    columns = OffColumns();
  }
  // Counts beyond the file size are rejected before anything is allocated.
  const uint64_t left = text.size() - std::min(text.size(), scan.pos);
  if (counts[0] > left / kMinVertexBytes || counts[1] > left / kMinFaceBytes || counts[0] > 0xFFFFFFFFull)
    throw fail("header counts (" + std::to_string(counts[0]) + " vertices, " +
               std::to_string(counts[1]) + " faces) are larger than the file can hold");

  Mesh mesh;
  mesh.source_positions.reserve(counts[0] * 3);
  mesh.triangles.reserve(counts[1] * 3);
  OffExtra extra;
  for (uint64_t v = 0; v < counts[0]; ++v) {
    if (!content_line(scan, line))
      throw Error(name + ": truncated: the header says " + std::to_string(counts[0]) +
                  " vertices but the file ends after " + std::to_string(v));
    const std::string problem = take_xyz(line, mesh.source_positions);
    if (!problem.empty()) throw fail(problem);
    if (columns.normals || columns.colours || columns.texcoords) {
      const std::string more = take_off_columns(line, columns, extra);
      if (!more.empty()) throw fail(more);
    }
  }
  std::vector<uint32_t> poly;
  for (uint64_t f = 0; f < counts[1]; ++f) {
    if (!content_line(scan, line))
      throw Error(name + ": truncated: the header says " + std::to_string(counts[1]) +
                  " faces but the file ends after " + std::to_string(f));
    std::string_view tok = next_token(line);
    uint64_t n;
    if (!parse_number(tok, n)) throw fail("bad face vertex count " + quoted(tok));
    if (const std::string problem = polygon_size_problem(n); !problem.empty()) throw fail(problem);
    poly.clear();
    for (uint64_t i = 0; i < n; ++i) {
      tok = next_token(line);
      int64_t idx;
      if (tok.empty()) throw fail("face lists fewer than its " + std::to_string(n) + " indices");
      if (!parse_number(tok, idx)) throw fail("bad face index " + quoted(tok));
      if (idx < 0 || idx >= static_cast<int64_t>(counts[0]))
        throw fail("face index " + std::to_string(idx) + " is out of range (" +
                   std::to_string(counts[0]) + " vertices)");
      poly.push_back(static_cast<uint32_t>(idx));
    }
    append_fan(mesh.triangles, poly.data(), poly.size());
    // Whatever follows (a colour) is ignored.
  }
  if (content_line(scan, line))
    throw fail("more data after the " + std::to_string(counts[1]) +
               " faces the header announces");
  add_off_attributes(mesh, columns, std::move(extra));
  localize_read_positions(mesh);
  return mesh;
}

}  // namespace meshsal
