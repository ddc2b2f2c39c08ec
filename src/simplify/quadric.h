// meshsal: Garland-Heckbert error quadrics (symmetric 4x4, 10 doubles) and the optimal
// contraction target of an edge (SPEC 2).
#pragma once

namespace meshsal {

// Q = [A b; b^T c] with A symmetric 3x3; the error of a point p is p^T A p + 2 b.p + c.
struct Quadric {
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0;
  double b0 = 0, b1 = 0, b2 = 0;
  double c = 0;

  // Inline: the simplifier sums and evaluates quadrics about ten times per collapse.
  Quadric& operator+=(const Quadric& q) {
    a00 += q.a00; a01 += q.a01; a02 += q.a02; a11 += q.a11; a12 += q.a12; a22 += q.a22;
    b0 += q.b0; b1 += q.b1; b2 += q.b2;
    c += q.c;
    return *this;
  }
  Quadric& operator*=(double s) {
    a00 *= s; a01 *= s; a02 *= s; a11 *= s; a12 *= s; a22 *= s;
    b0 *= s; b1 *= s; b2 *= s;
    c *= s;
    return *this;
  }
  // Error of point p (clamped at 0: rounding can make it slightly negative).
  double error(const double p[3]) const {
    const double x = p[0], y = p[1], z = p[2];
    const double e = a00 * x * x + a11 * y * y + a22 * z * z +
                     2 * (a01 * x * y + a02 * x * z + a12 * y * z) +
                     2 * (b0 * x + b1 * y + b2 * z) + c;
    return e > 0 ? e : 0;
  }
};

inline Quadric operator+(Quadric a, const Quadric& b) { return a += b; }

// Quadric of the plane n.x + d = 0 (n unit length) times `weight`: weight * dist(p)^2.
Quadric plane_quadric(const double n[3], double d, double weight);

// Area-weighted quadric of triangle (p0, p1, p2): area * (distance to its plane)^2.
// A zero-area triangle gives the zero quadric.
Quadric triangle_quadric(const double p0[3], const double p1[3], const double p2[3]);

// Border quadric of edge (p0, p1) of a triangle whose third corner is p2: the plane that
// contains the edge and is perpendicular to the triangle, weighted by weight * |p1-p0|^2,
// so that moving a border vertex off its border line costs error.
Quadric border_quadric(const double p0[3], const double p1[3], const double p2[3],
                       double weight);

// Where to place the vertex that replaces edge (p0, p1) under quadric q, and its error.
// Optimal placement solves A x = -b; when A is singular (|det A| <= 1e-6 * (trace A / 3)^3,
// i.e. numerically rank deficient, e.g. a flat or cylindrical neighbourhood) the best of
// p0, p1 and their midpoint is used (first minimum in that order). Returns the error.
// The threshold is relative, so the choice does not depend on the scale (or weight) of q.
double optimal_placement(const Quadric& q, const double p0[3], const double p1[3],
                         double out[3], bool* used_fallback = nullptr);

}  // namespace meshsal
