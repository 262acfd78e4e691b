#pragma once
// Signs of orientation determinants in double precision with a certified error bound (a
// floating-point filter): the sign is returned only when rounding cannot have changed it, and
// otherwise the caller asks the exact predicates (CGAL's, in part_overlap.cpp).
//
// orientation(o, a, b, x) is the sign of det[a - o, b - o, x - o] = (x - o) . ((a - o) x (b - o)),
// as CGAL::orientation(o, a, b, x). Computed in doubles as a sum of three products of a rounded
// difference with a 2 x 2 minor of rounded differences, its error is at most
//   (7 + 56 eps) eps P,   P = sum_i |x_i - o_i| (|ad_j bd_k| + |ad_k bd_j|)   (eps = 2^-53),
// the bound of Shewchuk's orient3d (J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic
// and Fast Robust Geometric Predicates", Discrete Comput. Geom. 18:305-363, 1997: orient3d's
// first error bound, errboundA, with P evaluated in floating point). The bound depends only on the
// shape of the expression, the same along any row or column of the determinant, so it holds for
// this expansion along x - o. Each face's normal n = (a - o) x (b - o) and S = sum_i N_i, N_i =
// |ad_j bd_k| + |ad_k bd_j|, are computed once (FacePlane); for a point, max_i |x_i - o_i| * S
// bounds P from above to within a few roundings, so 8 eps * max|x - o| * S >= the bound above
// (8 eps = 2^-50: multiplying by it is exact), and a computed determinant larger in magnitude
// has the exact sign.
//
// The same way, a component of n is a 2 x 2 determinant (an orient2d of the corners projected
// on a coordinate plane) with error at most (3 + 16 eps) eps N_i (Shewchuk, errboundA of
// orient2d): larger than 4 eps N_i = 2^-51 N_i, it is certainly not zero, and the face is
// certainly not degenerate (its corners are not collinear).
//
// Shewchuk's bounds assume that no operation underflows or overflows. They are used only for
// faces whose coordinates are each 0 or of magnitude in [2^-250, 2^300] (in_filter_range): then
// every non-zero difference lies in [2^-302, 2^301], every non-zero product and determinant
// between 2^-958 and 2^906, all normal doubles. Other faces go to the exact predicates.
// Compiled without contraction into fused multiply-adds (-ffp-contract=off), whose different
// rounding the bound does not cover.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace tumble::engine::detail {

/// A face's plane through its first corner o: n = (a - o) x (b - o) as rounded, and the sum S
/// of the magnitudes of the six products (the permanent's factor, see above).
struct FacePlane {
  double n[3];
  double s;
};

/// Whether a coordinate keeps the filter free of underflow and overflow (see above).
inline bool in_filter_range(double c) {
  const double magnitude = std::abs(c);
  // Bitwise: no branches where many coordinates are tested in a row.
  return (c == 0.0) | ((magnitude >= 0x1p-250) & (magnitude <= 0x1p300));
}

/// The plane of face (o, a, b); `certainly_not_collinear` is set when a component of the normal
/// is certainly non-zero (else the exact predicates decide).
inline FacePlane face_plane(const Eigen::Vector3d& o, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, bool& certainly_not_collinear) {
  const double adx = a.x() - o.x(), ady = a.y() - o.y(), adz = a.z() - o.z();
  const double bdx = b.x() - o.x(), bdy = b.y() - o.y(), bdz = b.z() - o.z();
  const double yz = ady * bdz, zy = adz * bdy, zx = adz * bdx, xz = adx * bdz;
  const double xy = adx * bdy, yx = ady * bdx;
  FacePlane plane;
  plane.n[0] = yz - zy;
  plane.n[1] = zx - xz;
  plane.n[2] = xy - yx;
  const double nx = std::abs(yz) + std::abs(zy), ny = std::abs(zx) + std::abs(xz);
  const double nz = std::abs(xy) + std::abs(yx);
  plane.s = nx + ny + nz;
  constexpr double kMinorBound = 0x1p-51;  // 4 eps, above orient2d's (3 + 16 eps) eps
  certainly_not_collinear = std::abs(plane.n[0]) > kMinorBound * nx ||
                            std::abs(plane.n[1]) > kMinorBound * ny ||
                            std::abs(plane.n[2]) > kMinorBound * nz;
  return plane;
}

/// The sign of orientation(o, a, b, x) for the face (o, a, b) of `plane`: +1 or -1 when
/// certain, 0 when rounding could have changed it (including an exact zero).
inline int certified_side(const FacePlane& plane, const Eigen::Vector3d& o,
                          const Eigen::Vector3d& x) {
  const double dx = x.x() - o.x(), dy = x.y() - o.y(), dz = x.z() - o.z();
  const double det = dx * plane.n[0] + dy * plane.n[1] + dz * plane.n[2];
  const double reach = std::max({std::abs(dx), std::abs(dy), std::abs(dz)});
  constexpr double kOrientationBound = 0x1p-50;  // 8 eps, above orient3d's (7 + 56 eps) eps
  const double bound = kOrientationBound * (reach * plane.s);
  return det > bound ? 1 : (-det > bound ? -1 : 0);
}

/// The sign of the orientation of points a, b, c of a plane (positive counter-clockwise) when
/// certain, else 0: Shewchuk's orient2d with its first error bound (see above).
inline int certified_orientation_2d(double ax, double ay, double bx, double by, double cx,
                                    double cy) {
  const double left = (ax - cx) * (by - cy), right = (ay - cy) * (bx - cx);
  const double det = left - right;
  constexpr double kMinorBound = 0x1p-51;  // 4 eps, above orient2d's (3 + 16 eps) eps
  const double bound = kMinorBound * (std::abs(left) + std::abs(right));
  return det > bound ? 1 : (-det > bound ? -1 : 0);
}

/// The sign of orientation(p, q, r, s) (CGAL's: det[q - p, r - p, s - p]) when certain, else 0.
inline int certified_orientation(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                 const Eigen::Vector3d& r, const Eigen::Vector3d& s) {
  bool unused = false;
  return certified_side(face_plane(p, q, r, unused), p, s);
}

}  // namespace tumble::engine::detail
