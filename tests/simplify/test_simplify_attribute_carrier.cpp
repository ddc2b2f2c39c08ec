// The simplifier's attribute carrier (src/simplify/attribute_carrier.*): values follow the
// internal vertex order, a collapse interpolates along the edge at the survivor's
// projection, and normals that moved come out unit length.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "meshsal/meshsal.h"
#include "simplify/attribute_carrier.h"

using namespace meshsal;
using detail::AttributeCarrier;

namespace {

Mesh three_vertices() {
  Mesh m;
  m.positions.assign(9, 0.f);
  m.attributes.push_back({"u", {0.f, 10.f, 20.f}});
  m.attributes.push_back({"nx", {1.f, 0.f, 0.f}});
  m.attributes.push_back({"ny", {0.f, 1.f, 0.f}});
  m.attributes.push_back({"nz", {0.f, 0.f, 1.f}});
  return m;
}

}  // namespace

TEST_CASE("attribute carrier: interpolation along the edge, normals renormalised", "[simplify]") {
  const Mesh m = three_vertices();
  AttributeCarrier c;
  const std::vector<uint32_t> order = {2, 0, 1};  // internal -> input
  const std::vector<uint32_t> inv = {1, 2, 0};    // input -> internal
  c.take(m, order);
  CHECK_FALSE(c.empty());
  // Internal 1 (input 0, u = 0) takes internal 2 (input 1, u = 10); the survivor lands a
  // quarter of the way, projected onto the edge.
  const double pa[3] = {0, 0, 0}, pb[3] = {4, 0, 0}, np[3] = {1, 3, 0};
  c.carry(1, 2, pa, pb, np);
  // Beyond the far end: clamped to b's values.
  const double far[3] = {9, 0, 0};
  c.carry(0, 2, pa, pb, far);
  Mesh out;
  std::vector<uint32_t> changed = {1, 1, 0};  // internal 2 never moved
  c.write(m, {0, 1, 2}, inv, changed, &out);
  REQUIRE(out.attributes.size() == 4);
  CHECK(out.attributes[0].name == "u");
  CHECK(out.attributes[0].values[0] == Approx(2.5));  // input 0: 0 + (10 - 0) / 4
  CHECK(out.attributes[0].values[1] == 10.f);          // input 1: untouched
  CHECK(out.attributes[0].values[2] == 10.f);          // input 2: took input 1's, t = 1
  // Input 0's normal: (1, 0, 0) three quarters, (0, 1, 0) one quarter, then unit length.
  const double len = std::sqrt(0.75 * 0.75 + 0.25 * 0.25);
  CHECK(out.attributes[1].values[0] == Approx(0.75 / len));
  CHECK(out.attributes[2].values[0] == Approx(0.25 / len));
  CHECK(out.attributes[3].values[0] == 0.f);
  CHECK(out.attributes[2].values[1] == 1.f);  // never moved: exactly the input's
}

TEST_CASE("attribute carrier: a zero-length edge keeps a's values, and bad sizes are errors", "[simplify]") {
  Mesh m = three_vertices();
  AttributeCarrier c;
  c.take(m, {0, 1, 2});
  const double p[3] = {1, 1, 1};
  c.carry(0, 1, p, p, p);
  Mesh out;
  c.write(m, {0}, {0, 1, 2}, {1, 0, 0}, &out);
  CHECK(out.attributes[0].values[0] == 0.f);
  m.attributes[0].values.pop_back();
  AttributeCarrier bad;
  CHECK_THROWS_AS(bad.take(m, {0, 1, 2}), Error);
  AttributeCarrier none;
  none.take(Mesh{}, {});
  CHECK(none.empty());
}
