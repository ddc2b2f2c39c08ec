// meshsal: OFF reader. Accepts the OFF / COFF / NOFF / CNOFF / STOFF... header keywords
// (extra vertex columns such as normals or colours are ignored), '#' comments, counts on
// the header line or the next, and optional colour columns after a face's indices.
// One vertex or face per line, as every OFF writer does.
#include <algorithm>
#include <string>
#include <string_view>

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

// Reads the keyword and the vertex / face counts; leaves `scan` after the counts line.
void parse_off_header(TextScan& scan, uint64_t counts[2]) {
  std::string_view line;
  scan.skip_bom();
  if (!content_line(scan, line)) throw Error(scan.name + ": empty file");
  std::string_view keyword = next_token(line);
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF")
    throw line_error(scan, "not an OFF file (the first word is " + quoted(keyword) + ", expected OFF)");
  for (char c : keyword.substr(0, keyword.size() - 3))
    if (c != 'C' && c != 'N' && c != 'S' && c != 'T')
      throw line_error(scan, "unsupported OFF variant " + quoted(keyword));
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

Mesh load_off_text(std::string_view text, const std::string& name) {
  TextScan scan(text, name);
  std::string_view line;
  auto fail = [&](const std::string& problem) { return line_error(scan, problem); };
  uint64_t counts[2];
  parse_off_header(scan, counts);
  // Counts beyond the file size are rejected before anything is allocated.
  const uint64_t left = text.size() - std::min(text.size(), scan.pos);
  if (counts[0] > left / kMinVertexBytes || counts[1] > left / kMinFaceBytes || counts[0] > 0xFFFFFFFFull)
    throw fail("header counts (" + std::to_string(counts[0]) + " vertices, " +
               std::to_string(counts[1]) + " faces) are larger than the file can hold");

  Mesh mesh;
  mesh.source_positions.reserve(counts[0] * 3);
  mesh.triangles.reserve(counts[1] * 3);
  for (uint64_t v = 0; v < counts[0]; ++v) {
    if (!content_line(scan, line))
      throw Error(name + ": truncated: the header says " + std::to_string(counts[0]) +
                  " vertices but the file ends after " + std::to_string(v));
    const std::string problem = take_xyz(line, mesh.source_positions);
    if (!problem.empty()) throw fail(problem);
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
  localize_read_positions(mesh);
  return mesh;
}

}  // namespace meshsal
