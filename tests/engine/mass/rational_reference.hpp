#pragma once
/// @file An exact-rational oracle for the mass properties of a closed triangle mesh (tests only).
///
/// Every double coordinate is an exact rational, so the volume integrals of the polyhedron the
/// mesh describes are exact rationals too. This oracle sums them in GMP arithmetic about the
/// world origin (not about a nearby reference point, as the engine does), using the moments of
/// the tetrahedron (0, a, b, c) from the Dirichlet integrals over the unit simplex:
///   int 1 = D/6,  int x_i = D/24 (a + b + c)_i,  int x_i x_j = D/120 (sum_v v_i v_j + s_i s_j),
/// with D = det[a b c] and s = a + b + c. Only the final values are rounded to double.

#include <gmpxx.h>

#include <Eigen/Core>
#include <array>
#include <cstddef>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine::rational_reference {

/// Exact integrals of 1, x and x x^T over the solid, about the origin.
struct RationalIntegrals {
  mpq_class volume;
  std::array<mpq_class, 3> first;
  std::array<std::array<mpq_class, 3>, 3> second;
};

/// Mass properties rounded to double from their exact values.
struct ReferenceMassProperties {
  double volume = 0.0;
  double mass = 0.0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the centre of mass
};

inline RationalIntegrals rational_solid_integrals(const TriangleMesh& mesh) {
  RationalIntegrals sums;
  for (auto& row : sums.second) {
    for (auto& entry : row) entry = 0;
  }
  for (auto& entry : sums.first) entry = 0;
  sums.volume = 0;

  std::array<std::array<mpq_class, 3>, 3> v;
  for (const auto& triangle : mesh.triangles) {
    // Exact rational corners (mpq_class(double) is exact).
    for (int corner = 0; corner < 3; ++corner) {
      const Eigen::Vector3d& p = mesh.positions[triangle[static_cast<std::size_t>(corner)]];
      for (int axis = 0; axis < 3; ++axis) {
        v[static_cast<std::size_t>(corner)][static_cast<std::size_t>(axis)] = mpq_class(p[axis]);
      }
    }
    const auto& a = v[0];
    const auto& b = v[1];
    const auto& c = v[2];
    const mpq_class det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                          a[2] * (b[0] * c[1] - b[1] * c[0]);
    if (det == 0) continue;
    std::array<mpq_class, 3> s;
    for (std::size_t i = 0; i < 3; ++i) s[i] = a[i] + b[i] + c[i];

    sums.volume += det;
    for (std::size_t i = 0; i < 3; ++i) sums.first[i] += det * s[i];
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t j = i; j < 3; ++j) {
        sums.second[i][j] += det * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
      }
    }
  }

  sums.volume /= 6;
  for (std::size_t i = 0; i < 3; ++i) sums.first[i] /= 24;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = i; j < 3; ++j) {
      sums.second[i][j] /= 120;
      sums.second[j][i] = sums.second[i][j];
    }
  }
  return sums;
}

/// Exact mass properties of uniform matter of `density` filling the closed mesh.
inline ReferenceMassProperties rational_mass_properties(const TriangleMesh& mesh, double density) {
  const RationalIntegrals sums = rational_solid_integrals(mesh);
  const mpq_class rho(density);

  // Centre of mass, then the second moment about it (exact, so no cancellation matters).
  std::array<mpq_class, 3> center;
  for (std::size_t i = 0; i < 3; ++i) center[i] = sums.first[i] / sums.volume;
  std::array<std::array<mpq_class, 3>, 3> centred;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      centred[i][j] = sums.second[i][j] - sums.volume * center[i] * center[j];
    }
  }
  const mpq_class trace = centred[0][0] + centred[1][1] + centred[2][2];

  ReferenceMassProperties out;
  out.volume = sums.volume.get_d();
  out.mass = mpq_class(rho * sums.volume).get_d();
  for (std::size_t i = 0; i < 3; ++i) {
    out.center_of_mass[static_cast<Eigen::Index>(i)] = center[i].get_d();
    for (std::size_t j = 0; j < 3; ++j) {
      const mpq_class entry = rho * ((i == j ? trace : mpq_class(0)) - centred[i][j]);
      out.inertia(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = entry.get_d();
    }
  }
  return out;
}

}  // namespace tumble::engine::rational_reference
