#include "engine/geometry/primitive_meshes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace tumble::engine {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

std::uint32_t to_index(std::size_t i) {
  if (i > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("mesh too large for 32-bit vertex indices");
  }
  return static_cast<std::uint32_t>(i);
}

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument(message);
}

void require_positive(double value, const std::string& what) {
  require(std::isfinite(value) && value > 0.0,
          what + " must be positive and finite, got " + std::to_string(value));
}

void require_count(int count, int minimum, const std::string& what) {
  require(count >= minimum,
          what + " must be at least " + std::to_string(minimum) + ", got " + std::to_string(count));
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Twice the signed area of the closed polygon (positive when counter-clockwise).
double twice_signed_area(const std::vector<Eigen::Vector2d>& polygon) {
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    sum += cross2(polygon[i], polygon[(i + 1) % polygon.size()]);
  }
  return sum;
}

/// Whether `p` lies inside or on the counter-clockwise triangle (a, b, c).
bool in_closed_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return cross2(b - a, p - a) >= 0.0 && cross2(c - b, p - b) >= 0.0 && cross2(a - c, p - c) >= 0.0;
}

/// 4 sqrt(3) area / (sum of squared edges): 1 for an equilateral triangle, 0 for a sliver.
double triangle_quality(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        const Eigen::Vector2d& c) {
  const double edges = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return 2.0 * std::numbers::sqrt3 * cross2(b - a, c - a) / edges;
}

/// Triangulates a simple counter-clockwise polygon by ear clipping, always cutting the
/// best-shaped ear (Meisters, "Polygons have ears", Amer. Math. Monthly 82 (1975)).
std::vector<Triangle> ear_clip(const std::vector<Eigen::Vector2d>& polygon) {
  std::vector<std::uint32_t> remaining(polygon.size());
  for (std::size_t i = 0; i < remaining.size(); ++i) remaining[i] = to_index(i);

  std::vector<Triangle> triangles;
  triangles.reserve(polygon.size() - 2);
  std::vector<std::uint32_t> reflex;
  while (remaining.size() > 3) {
    const std::size_t count = remaining.size();
    auto corner = [&](std::size_t k, std::size_t offset) {
      return remaining[(k + offset) % count];
    };

    // Reflex (or flat) corners are the only ones that can lie inside an ear.
    reflex.clear();
    for (std::size_t k = 0; k < count; ++k) {
      const auto& a = polygon[corner(k, count - 1)];
      const auto& b = polygon[corner(k, 0)];
      const auto& c = polygon[corner(k, 1)];
      if (cross2(b - a, c - b) <= 0.0) reflex.push_back(corner(k, 0));
    }

    // Pick the convex corner whose empty ear has the best shape.
    std::size_t best = count;
    double best_quality = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t ia = corner(k, count - 1);
      const std::uint32_t ib = corner(k, 0);
      const std::uint32_t ic = corner(k, 1);
      const auto& a = polygon[ia];
      const auto& b = polygon[ib];
      const auto& c = polygon[ic];
      if (cross2(b - a, c - b) <= 0.0) continue;
      const double quality = triangle_quality(a, b, c);
      if (quality <= best_quality) continue;
      const bool empty = std::none_of(reflex.begin(), reflex.end(), [&](std::uint32_t v) {
        return v != ia && v != ic && in_closed_triangle(polygon[v], a, b, c);
      });
      if (!empty) continue;
      best = k;
      best_quality = quality;
    }
    require(best < count, "extrude_polygon: the outline is not a simple polygon");

    // Cut it off.
    triangles.push_back({corner(best, count - 1), corner(best, 0), corner(best, 1)});
    remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(best));
  }
  const auto& a = polygon[remaining[0]];
  const auto& b = polygon[remaining[1]];
  const auto& c = polygon[remaining[2]];
  require(cross2(b - a, c - b) > 0.0, "extrude_polygon: the outline is not a simple polygon");
  triangles.push_back({remaining[0], remaining[1], remaining[2]});
  return triangles;
}

/// Adds the planar quad (a, b, c, d), given in cyclic order, as two triangles facing `outward`.
void add_quad_facing(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                     std::uint32_t d, const Eigen::Vector3d& outward) {
  const auto& p = mesh.positions;
  const Eigen::Vector3d normal = (p[b] - p[a]).cross(p[c] - p[a]);
  if (normal.dot(outward) > 0.0) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
  } else {
    mesh.triangles.push_back({a, c, b});
    mesh.triangles.push_back({a, d, c});
  }
}

}  // namespace

TriangleMesh box_mesh(const Eigen::Vector3d& size) {
  for (int axis = 0; axis < 3; ++axis) require_positive(size[axis], "box_mesh: size");

  // Corner k has coordinate bit `axis` of k set when it lies on the positive side.
  TriangleMesh mesh;
  for (std::uint32_t k = 0; k < 8; ++k) {
    Eigen::Vector3d corner;
    for (int axis = 0; axis < 3; ++axis) {
      corner[axis] = ((k >> axis) & 1u) != 0u ? 0.5 * size[axis] : -0.5 * size[axis];
    }
    mesh.positions.push_back(corner);
  }

  // One quad per face, corners in cyclic order over the two other axes.
  for (int axis = 0; axis < 3; ++axis) {
    const std::uint32_t u = 1u << ((axis + 1) % 3);
    const std::uint32_t v = 1u << ((axis + 2) % 3);
    for (std::uint32_t side = 0; side < 2; ++side) {
      const std::uint32_t base = side << axis;
      Eigen::Vector3d outward = Eigen::Vector3d::Zero();
      outward[axis] = side == 1 ? 1.0 : -1.0;
      add_quad_facing(mesh, base, base | u, base | u | v, base | v, outward);
    }
  }
  return mesh;
}

TriangleMesh tetrahedron_mesh(const std::array<Eigen::Vector3d, 4>& corners) {
  const double det =
      (corners[1] - corners[0]).cross(corners[2] - corners[0]).dot(corners[3] - corners[0]);
  require(std::isfinite(det) && det != 0.0, "tetrahedron_mesh: the corners are coplanar");

  // With det > 0 these faces point outward; otherwise swap two corners.
  TriangleMesh mesh;
  mesh.positions.assign(corners.begin(), corners.end());
  if (det < 0.0) std::swap(mesh.positions[1], mesh.positions[2]);
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return mesh;
}

TriangleMesh revolve_profile(const std::vector<Eigen::Vector2d>& profile_rz, int segments) {
  require_count(segments, 3, "revolve_profile: segments");
  require(profile_rz.size() >= 3, "revolve_profile: the profile needs at least 3 points");
  require(profile_rz.front().x() == 0.0 && profile_rz.back().x() == 0.0,
          "revolve_profile: the first and last profile points must lie on the axis (r = 0)");
  for (std::size_t i = 0; i < profile_rz.size(); ++i) {
    const auto& point = profile_rz[i];
    require(point.allFinite(),
            "revolve_profile: profile point " + std::to_string(i) + " is not finite");
    if (i > 0) {
      require(point != profile_rz[i - 1],
              "revolve_profile: profile point " + std::to_string(i) + " repeats the previous one");
    }
    if (i > 0 && i + 1 < profile_rz.size()) {
      require(point.x() > 0.0,
              "revolve_profile: profile point " + std::to_string(i) + " must have r > 0");
    }
  }

  // Travel counter-clockwise in the (r, z) half-plane, which makes the winding below outward.
  std::vector<Eigen::Vector2d> profile = profile_rz;
  const double area = twice_signed_area(profile);
  require(area != 0.0, "revolve_profile: the profile encloses no area");
  if (area < 0.0) std::reverse(profile.begin(), profile.end());

  // Vertices: bottom apex, one regular polygon per interior profile point, top apex.
  const std::size_t n = static_cast<std::size_t>(segments);
  TriangleMesh mesh;
  mesh.positions.reserve((profile.size() - 2) * n + 2);
  mesh.positions.emplace_back(0.0, 0.0, profile.front().y());
  for (std::size_t i = 1; i + 1 < profile.size(); ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      const double angle = 2.0 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(n);
      const double r = profile[i].x();
      mesh.positions.emplace_back(r * std::cos(angle), r * std::sin(angle), profile[i].y());
    }
  }
  mesh.positions.emplace_back(0.0, 0.0, profile.back().y());
  const std::uint32_t bottom = 0;
  const std::uint32_t top = to_index(mesh.positions.size() - 1);
  auto ring = [n](std::size_t i, std::size_t j) { return to_index(1 + (i - 1) * n + j % n); };

  // Fan at the bottom apex, trapezoid strips between rings, fan at the top apex.
  const std::size_t last = profile.size() - 2;
  for (std::size_t j = 0; j < n; ++j)
    mesh.triangles.push_back({bottom, ring(1, j + 1), ring(1, j)});
  for (std::size_t i = 1; i < last; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      mesh.triangles.push_back({ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)});
      mesh.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
    }
  }
  for (std::size_t j = 0; j < n; ++j)
    mesh.triangles.push_back({ring(last, j), ring(last, j + 1), top});
  return mesh;
}

TriangleMesh ellipsoid_mesh(const Eigen::Vector3d& radii, int segments, int rings) {
  for (int axis = 0; axis < 3; ++axis) require_positive(radii[axis], "ellipsoid_mesh: radius");
  require_count(segments, 3, "ellipsoid_mesh: segments");
  require_count(rings, 2, "ellipsoid_mesh: rings");

  // A unit half circle from the south pole to the north pole, revolved, then stretched.
  std::vector<Eigen::Vector2d> profile;
  profile.emplace_back(0.0, -1.0);
  for (int k = 1; k < rings; ++k) {
    const double polar = std::numbers::pi * static_cast<double>(k) / static_cast<double>(rings);
    profile.emplace_back(std::sin(polar), -std::cos(polar));
  }
  profile.emplace_back(0.0, 1.0);
  TriangleMesh mesh = revolve_profile(profile, segments);
  for (auto& position : mesh.positions) position = position.cwiseProduct(radii);
  return mesh;
}

TriangleMesh uv_sphere_mesh(double radius, int segments, int rings) {
  require_positive(radius, "uv_sphere_mesh: radius");
  return ellipsoid_mesh(Eigen::Vector3d::Constant(radius), segments, rings);
}

TriangleMesh cylinder_mesh(double radius, double height, int segments) {
  require_positive(radius, "cylinder_mesh: radius");
  require_positive(height, "cylinder_mesh: height");
  require_count(segments, 3, "cylinder_mesh: segments");
  const double half = 0.5 * height;
  return revolve_profile({{0.0, -half}, {radius, -half}, {radius, half}, {0.0, half}}, segments);
}

TriangleMesh cone_mesh(double radius, double height, int segments) {
  require_positive(radius, "cone_mesh: radius");
  require_positive(height, "cone_mesh: height");
  require_count(segments, 3, "cone_mesh: segments");
  return revolve_profile({{0.0, 0.0}, {radius, 0.0}, {0.0, height}}, segments);
}

TriangleMesh torus_mesh(double major_radius, double minor_radius, int major_segments,
                        int minor_segments) {
  require_positive(major_radius, "torus_mesh: major radius");
  require_positive(minor_radius, "torus_mesh: minor radius");
  require(minor_radius < major_radius, "torus_mesh: the minor radius must be below the major one");
  require_count(major_segments, 3, "torus_mesh: major segments");
  require_count(minor_segments, 3, "torus_mesh: minor segments");

  // Vertex (i, j): angle i around the z axis, angle j around the tube (0 = outermost).
  const std::size_t n = static_cast<std::size_t>(major_segments);
  const std::size_t m = static_cast<std::size_t>(minor_segments);
  TriangleMesh mesh;
  mesh.positions.reserve(n * m);
  for (std::size_t i = 0; i < n; ++i) {
    const double around = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
    for (std::size_t j = 0; j < m; ++j) {
      const double tube = 2.0 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(m);
      const double rho = major_radius + minor_radius * std::cos(tube);
      mesh.positions.emplace_back(rho * std::cos(around), rho * std::sin(around),
                                  minor_radius * std::sin(tube));
    }
  }
  auto vertex = [n, m](std::size_t i, std::size_t j) { return to_index((i % n) * m + j % m); };

  // d/d(around) x d/d(tube) points out of the tube, so this winding is outward.
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < m; ++j) {
      mesh.triangles.push_back({vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)});
      mesh.triangles.push_back({vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)});
    }
  }
  return mesh;
}

TriangleMesh extrude_polygon(const std::vector<Eigen::Vector2d>& outline_xy, double z0, double z1) {
  require(outline_xy.size() >= 3, "extrude_polygon: the outline needs at least 3 points");
  require(std::isfinite(z0) && std::isfinite(z1) && z0 != z1,
          "extrude_polygon: z0 and z1 must be finite and distinct");
  for (std::size_t i = 0; i < outline_xy.size(); ++i) {
    require(outline_xy[i].allFinite(),
            "extrude_polygon: outline point " + std::to_string(i) + " is not finite");
    require(outline_xy[i] != outline_xy[(i + 1) % outline_xy.size()],
            "extrude_polygon: outline point " + std::to_string(i) + " repeats the next one");
  }

  // Counter-clockwise outline, bottom below top.
  std::vector<Eigen::Vector2d> outline = outline_xy;
  const double area = twice_signed_area(outline);
  require(area != 0.0, "extrude_polygon: the outline encloses no area");
  if (area < 0.0) std::reverse(outline.begin(), outline.end());
  const double z_bottom = std::min(z0, z1);
  const double z_top = std::max(z0, z1);
  const std::vector<Triangle> cap = ear_clip(outline);

  // Vertices: the bottom outline, then the top outline.
  const std::size_t n = outline.size();
  TriangleMesh mesh;
  mesh.positions.reserve(2 * n);
  for (const auto& point : outline) mesh.positions.emplace_back(point.x(), point.y(), z_bottom);
  for (const auto& point : outline) mesh.positions.emplace_back(point.x(), point.y(), z_top);
  const std::uint32_t up = to_index(n);

  // Bottom cap faces down (reversed), top cap faces up, walls face right of the outline.
  mesh.triangles.reserve(2 * cap.size() + 2 * n);
  for (const auto& t : cap) mesh.triangles.push_back({t[0], t[2], t[1]});
  for (const auto& t : cap) mesh.triangles.push_back({t[0] + up, t[1] + up, t[2] + up});
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t a = to_index(i);
    const std::uint32_t b = to_index((i + 1) % n);
    mesh.triangles.push_back({a, b, b + up});
    mesh.triangles.push_back({a, b + up, a + up});
  }
  return mesh;
}

TriangleMesh icosphere_mesh(double radius, int subdivisions) {
  require_positive(radius, "icosphere_mesh: radius");
  require(subdivisions >= 0 && subdivisions <= 10,
          "icosphere_mesh: subdivisions must be in [0, 10], got " + std::to_string(subdivisions));

  // Icosahedron: cyclic permutations of (0, +-1, +-phi); edge length 2.
  const double phi = std::numbers::phi;
  TriangleMesh mesh;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double a : {-1.0, 1.0}) {
      for (const double b : {-phi, phi}) {
        Eigen::Vector3d p;
        p[axis] = 0.0;
        p[(axis + 1) % 3] = a;
        p[(axis + 2) % 3] = b;
        mesh.positions.push_back(p.normalized());
      }
    }
  }

  // Its faces are the triples of mutually adjacent vertices, turned to face away from the centre.
  const double edge_squared = 4.0 / (1.0 + phi * phi);
  auto adjacent = [&](std::uint32_t i, std::uint32_t j) {
    return std::abs((mesh.positions[i] - mesh.positions[j]).squaredNorm() - edge_squared) < 1e-9;
  };
  for (std::uint32_t i = 0; i < 12; ++i) {
    for (std::uint32_t j = i + 1; j < 12; ++j) {
      for (std::uint32_t k = j + 1; k < 12; ++k) {
        if (!adjacent(i, j) || !adjacent(j, k) || !adjacent(i, k)) continue;
        const auto& p = mesh.positions;
        const double facing = (p[j] - p[i]).cross(p[k] - p[i]).dot(p[i] + p[j] + p[k]);
        mesh.triangles.push_back(facing > 0.0 ? Triangle{i, j, k} : Triangle{i, k, j});
      }
    }
  }

  // Split each triangle in four through its edge midpoints, pushed onto the unit sphere.
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto found = midpoints.find(key);
      if (found != midpoints.end()) return found->second;
      const std::uint32_t index = to_index(mesh.positions.size());
      mesh.positions.push_back((mesh.positions[a] + mesh.positions[b]).normalized());
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<Triangle> finer;
    finer.reserve(4 * mesh.triangles.size());
    for (const auto& [a, b, c] : mesh.triangles) {
      const std::uint32_t ab = midpoint(a, b);
      const std::uint32_t bc = midpoint(b, c);
      const std::uint32_t ca = midpoint(c, a);
      finer.push_back({a, ab, ca});
      finer.push_back({ab, b, bc});
      finer.push_back({ca, bc, c});
      finer.push_back({ab, bc, ca});
    }
    mesh.triangles = std::move(finer);
  }
  for (auto& position : mesh.positions) position *= radius;
  return mesh;
}

void append_mesh(TriangleMesh& into, const TriangleMesh& part) {
  const std::uint32_t offset = to_index(into.positions.size());
  require(
      into.positions.size() + part.positions.size() <= std::numeric_limits<std::uint32_t>::max(),
      "append_mesh: mesh too large for 32-bit vertex indices");
  into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
  into.triangles.reserve(into.triangles.size() + part.triangles.size());
  for (const auto& [a, b, c] : part.triangles) {
    into.triangles.push_back({a + offset, b + offset, c + offset});
  }
}

void transform_mesh(TriangleMesh& mesh, const Eigen::Matrix3d& linear,
                    const Eigen::Vector3d& translation) {
  for (auto& position : mesh.positions) position = linear * position + translation;
  if (linear.determinant() < 0.0) {
    for (auto& triangle : mesh.triangles) std::swap(triangle[1], triangle[2]);
  }
}

}  // namespace tumble::engine
