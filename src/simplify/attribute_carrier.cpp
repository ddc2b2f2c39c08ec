// meshsal (internal): attributes through the collapses, see attribute_carrier.h.
#include "simplify/attribute_carrier.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "simplify/triangle_bits.h"

namespace meshsal {
namespace detail {

void AttributeCarrier::take(const Mesh& mesh, const std::vector<uint32_t>& order) {
  const size_t nv = order.size();
  per_vertex_ = mesh.attributes.size();
  if (!per_vertex_) return;
  values_.resize(per_vertex_ * nv);
  for (size_t i = 0; i < per_vertex_; ++i) {
    const VertexAttribute& a = mesh.attributes[i];
    if (a.values.size() != nv)
      throw Error("simplify: attribute '" + a.name + "' has " + std::to_string(a.values.size()) +
                  " values for " + std::to_string(nv) + " vertices");
    for (size_t v = 0; v < nv; ++v) values_[per_vertex_ * v + i] = a.values[order[v]];
    const int k = a.name == "nx" ? 0 : a.name == "ny" ? 1 : a.name == "nz" ? 2 : -1;
    if (k >= 0 && normal_at_[k] < 0) normal_at_[k] = int(i);
  }
}

void AttributeCarrier::carry(uint32_t a, uint32_t b, const double pa[3], const double pb[3],
                             const double np[3]) {
  double d[3], e[3];
  for (int k = 0; k < 3; ++k) {
    d[k] = pb[k] - pa[k];
    e[k] = np[k] - pa[k];
  }
  const double dd = dot3(d, d);
  const double t = dd > 0 ? std::min(1.0, std::max(0.0, dot3(d, e) / dd)) : 0;
  float* xa = &values_[per_vertex_ * a];
  const float* xb = &values_[per_vertex_ * b];
  for (size_t i = 0; i < per_vertex_; ++i) xa[i] = float((1 - t) * double(xa[i]) + t * double(xb[i]));
}

void AttributeCarrier::write(const Mesh& in, const std::vector<uint32_t>& origin,
                             const std::vector<uint32_t>& inv, const std::vector<uint32_t>& moved,
                             Mesh* out) const {
  const size_t n = origin.size();
  for (size_t i = 0; i < per_vertex_; ++i) {
    VertexAttribute a{in.attributes[i].name, std::vector<float>(n)};
    for (size_t o = 0; o < n; ++o) a.values[o] = values_[per_vertex_ * inv[origin[o]] + i];
    out->attributes.push_back(std::move(a));
  }
  if (normal_at_[0] >= 0 && normal_at_[1] >= 0 && normal_at_[2] >= 0) {
    float* c[3] = {out->attributes[size_t(normal_at_[0])].values.data(),
                   out->attributes[size_t(normal_at_[1])].values.data(),
                   out->attributes[size_t(normal_at_[2])].values.data()};
    for (size_t o = 0; o < n; ++o) {
      if (moved[inv[origin[o]]] == 0) continue;  // never touched: the input's exact normal
      const double len = std::sqrt(double(c[0][o]) * c[0][o] + double(c[1][o]) * c[1][o] + double(c[2][o]) * c[2][o]);
      if (len > 0)
        for (int k = 0; k < 3; ++k) c[k][o] = float(c[k][o] / len);
    }
  }
}

}  // namespace detail
}  // namespace meshsal
