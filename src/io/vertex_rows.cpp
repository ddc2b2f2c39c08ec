// meshsal: ground truth as text rows `x y z ... value`, read and joined to a mesh's
// vertices at their positions (SPEC section 7).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh_points.h"
#include "core/model_frame.h"
#include "io/mesh_io_internal.h"
#include "io/read_bytes.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// The fields of one line, split at spaces, tabs and commas.
std::vector<std::string_view> fields_of(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == ',' || line[i] == '\r')) ++i;
    const size_t b = i;
    while (i < line.size() && !(line[i] == ' ' || line[i] == '\t' || line[i] == ',' || line[i] == '\r')) ++i;
    if (i > b) out.push_back(line.substr(b, i - b));
  }
  return out;
}

// The field as a number (the whole field; nan and inf parse, and are refused by the caller).
bool number_of(std::string_view field, double& out) {
  const std::string s(field);
  char* end = nullptr;
  errno = 0;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && !s.empty();
}

std::string where(const std::string& name, size_t line) { return name + ": line " + std::to_string(line) + ": "; }

}  // namespace

VertexRows parse_vertex_rows(const std::string& text, const std::string& name, int column) {
  if (column != 0 && column < 4)
    throw Error(name + ": the value's column must be 4 or more (x y z come first), got " + std::to_string(column));
  VertexRows r;
  size_t line_no = 0, pos = 0;
  bool first = true;
  std::vector<double> numbers;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_no;
    const std::vector<std::string_view> f = fields_of(line);
    if (f.empty() || f[0][0] == '#') continue;
    numbers.assign(f.size(), 0.0);
    bool all = true;
    size_t bad = 0;
    for (size_t i = 0; i < f.size() && all; ++i)
      if (!number_of(f[i], numbers[i])) all = false, bad = i;
    const bool was_first = first;
    first = false;
    if (!all) {
      if (was_first) continue;  // a header line
      throw Error(where(name, line_no) + "field " + std::to_string(bad + 1) + " '" + std::string(f[bad]) +
                  "' is not a number");
    }
    if (f.size() < 4)
      throw Error(where(name, line_no) + "a row needs x y z and a value, got " + std::to_string(f.size()) +
                  (f.size() == 1 ? " field" : " fields"));
    if (r.columns == 0) {
      r.columns = f.size();
      if (column > int(r.columns))
        throw Error(where(name, line_no) + "--gt-column " + std::to_string(column) + " is beyond its " +
                    std::to_string(r.columns) + " fields");
    } else if (f.size() != r.columns) {
      throw Error(where(name, line_no) + std::to_string(f.size()) + " fields, but the first row has " +
                  std::to_string(r.columns));
    }
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(numbers[k]))
        throw Error(where(name, line_no) + "coordinate " + std::string(1, char('x' + k)) + " is not finite ('" +
                    std::string(f[k]) + "')");
    const size_t c = column == 0 ? r.columns - 1 : size_t(column - 1);
    if (!std::isfinite(numbers[c]))
      throw Error(where(name, line_no) + "the value (column " + std::to_string(c + 1) + ") is not finite ('" +
                  std::string(f[c]) + "')");
    r.xyz.insert(r.xyz.end(), numbers.begin(), numbers.begin() + 3);
    r.values.push_back(numbers[c]);
    r.lines.push_back(line_no);
  }
  if (r.values.empty()) throw Error(name + ": no rows `x y z ... value` in it");
  return r;
}

VertexRows read_vertex_rows(const std::string& path, int column, uint64_t max_input_bytes) {
  const uint64_t limit = max_input_bytes ? max_input_bytes : kNoHeaderLimitBytes;
  Bytes raw = read_file(path, limit);
  std::string text;
  if (has_gzip_magic(raw.view())) {
    const Bytes inflated = gunzip(raw.view(), path, [&](std::string_view) { return limit; });
    text.assign(inflated.view());
  } else {
    if (raw.size > limit)
      throw Error(path + ": " + std::to_string(raw.size) + " bytes, more than the " + std::to_string(limit) +
                  " a ground-truth file may hold (MESHSAL_MAX_INPUT)");
    text.assign(raw.view());
  }
  return parse_vertex_rows(text, path, column);
}

JoinedRows join_vertex_rows(const Mesh& mesh, const VertexRows& rows) {
  const size_t n = mesh.vertex_count();
  const BoundingBox box = mesh_points_bbox(mesh, referenced_vertices(mesh));
  const double tol = 1e-6 * box.diagonal();
  // Every vertex in the cell of side `cell` (>= tol) its local double position falls in,
  // sorted by cell: a row's matches are in the 27 cells around its own.
  std::vector<double> local(3 * n);
  for (size_t v = 0; v < n; ++v) {
    double m[3];
    model_position(mesh, v, m);
    for (int k = 0; k < 3; ++k) local[3 * v + k] = m[k] - mesh.origin[k];
  }
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = HUGE_VAL, hi[k] = -HUGE_VAL;
  for (size_t v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], local[3 * v + k]), hi[k] = std::max(hi[k], local[3 * v + k]);
  // The cell is tol, but at least 2^-40 of the vertices' extent: vertices no triangle uses
  // may lie far from the mesh points (or those all coincide, tol 0), and a cell of tol would
  // then number a vertex's cell beyond int64_t (undefined behaviour). Rows beyond the
  // extent by more than tol are not looked up, so every cell number is within [-1, 2^40+1].
  double extent = 0;
  for (int k = 0; k < 3; ++k) extent = std::max(extent, hi[k] - lo[k]);
  const double cell = std::max({tol, std::ldexp(extent, -40), 1e-300});
  struct Key {
    int64_t c[3];
    bool operator<(const Key& o) const {
      return c[2] != o.c[2] ? c[2] < o.c[2] : c[1] != o.c[1] ? c[1] < o.c[1] : c[0] < o.c[0];
    }
  };
  auto key_of = [&](const double* x) {
    Key key;
    for (int k = 0; k < 3; ++k) key.c[k] = int64_t(std::floor((x[k] - lo[k]) / cell));
    return key;
  };
  std::vector<std::pair<Key, uint32_t>> sorted(n);
  for (size_t v = 0; v < n; ++v) sorted[v] = {key_of(&local[3 * v]), uint32_t(v)};
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return a.first < b.first || (!(b.first < a.first) && a.second < b.second);
  });

  JoinedRows out;
  out.values.assign(n, 0.0);
  out.has_value.assign(n, 0);
  std::vector<size_t> row_of(n, 0);  // the line that set each vertex's value
  out.rows = rows.values.size();
  for (size_t r = 0; r < out.rows; ++r) {
    double x[3];
    for (int k = 0; k < 3; ++k) x[k] = rows.xyz[3 * r + k] - mesh.origin[k];
    bool outside = false;
    for (int k = 0; k < 3; ++k) outside |= !(x[k] >= lo[k] - tol && x[k] <= hi[k] + tol);
    bool matched = false;
    if (!outside) {
      const Key centre = key_of(x);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const Key k{{centre.c[0] + dx, centre.c[1] + dy, centre.c[2] + dz}};
            auto it = std::lower_bound(sorted.begin(), sorted.end(), k,
                                       [](const auto& e, const Key& key) { return e.first < key; });
            for (; it != sorted.end() && !(k < it->first); ++it) {
              const uint32_t v = it->second;
              double d2 = 0;
              for (int c = 0; c < 3; ++c) d2 += (local[3 * v + c] - x[c]) * (local[3 * v + c] - x[c]);
              if (!(d2 <= tol * tol)) continue;
              matched = true;
              const double value = rows.values[r];
              if (out.has_value[v] && out.values[v] != value) {
                char buf[160];
                std::snprintf(buf, sizeof buf, "rows at lines %zu and %zu give vertex %u two values (%.9g and %.9g)",
                              row_of[v], rows.lines[r], v, out.values[v], value);
                throw Error(std::string(buf) + ": the ground truth must give each position one value");
              }
              if (!out.has_value[v]) row_of[v] = rows.lines[r];  // the first row that gave it
              out.values[v] = value;
              out.has_value[v] = 1;
            }
          }
    }
    if (matched) {
      ++out.matched_rows;
    } else {
      ++out.unmatched_rows;
      if (out.unmatched_lines.size() < 20) out.unmatched_lines.push_back(rows.lines[r]);
    }
  }
  for (uint8_t h : out.has_value) out.vertices_without_value += h == 0;
  return out;
}

}  // namespace meshsal
