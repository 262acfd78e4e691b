/// @file Writes the demo meshes of assets/meshes as Wavefront OBJ: `make_meshes OUTPUT_DIR`.
///
/// Every mesh is closed, outward-wound and in metres; parts of one mesh never overlap (their
/// volumes would count twice). The output is deterministic: no std::random distributions (their
/// output differs between standard libraries), only a small hash-based generator, so the same
/// build always writes byte-identical files, which tests/engine/assets_test.cpp checks.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/geometry/triangle_mesh.hpp"

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using tumble::engine::TriangleMesh;
constexpr double kPi = std::numbers::pi;

/// SplitMix64 (Steele, Lea, Flood, "Fast splittable pseudorandom number generators", 2014):
/// the same sequence on every platform.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  /// Uniform in [low, high), from the top 53 bits.
  double uniform(double low, double high) {
    const double unit = static_cast<double>(next() >> 11) * 0x1.0p-53;
    return low + (high - low) * unit;
  }

 private:
  std::uint64_t state_;
};

/// Number of equal pieces so that none is longer than `max_length` (at least `minimum`).
int pieces(double length, double max_length, int minimum) {
  return std::max(minimum, static_cast<int>(std::ceil(length / max_length)));
}

/// The polygon `corners` (counter-clockwise) with each corner replaced by a circular fillet of
/// the given radius (convex or concave alike), sampled so no edge exceeds `max_edge`.
std::vector<Vector2d> rounded_outline(const std::vector<Vector2d>& corners,
                                      const std::vector<double>& radii, double max_edge) {
  const std::size_t n = corners.size();
  struct Fillet {
    Vector2d centre, start, end;
    double radius;
  };
  std::vector<Fillet> fillets;
  for (std::size_t i = 0; i < n; ++i) {
    // Tangent points at distance r / tan(half angle) along both edges.
    const Vector2d& p = corners[i];
    const Vector2d u = (corners[(i + n - 1) % n] - p).normalized();
    const Vector2d v = (corners[(i + 1) % n] - p).normalized();
    const double half = 0.5 * std::acos(std::clamp(u.dot(v), -1.0, 1.0));
    const double along = radii[i] / std::tan(half);
    fillets.push_back({p + (u + v).normalized() * (radii[i] / std::sin(half)), p + along * u,
                       p + along * v, radii[i]});
  }

  std::vector<Vector2d> outline;
  auto add = [&](const Vector2d& point) {
    if (outline.empty() || (point - outline.back()).norm() > 1e-12) outline.push_back(point);
  };
  for (std::size_t i = 0; i < n; ++i) {
    // The arc, the short way round from one tangent point to the other.
    const Fillet& f = fillets[i];
    const double a0 = std::atan2(f.start.y() - f.centre.y(), f.start.x() - f.centre.x());
    const double a1 = std::atan2(f.end.y() - f.centre.y(), f.end.x() - f.centre.x());
    const double sweep = std::remainder(a1 - a0, 2.0 * kPi);
    const int arc_pieces = pieces(std::abs(sweep) * f.radius, max_edge, 6);
    add(f.start);
    for (int k = 1; k < arc_pieces; ++k) {
      const double a = a0 + sweep * k / arc_pieces;
      add(f.centre + f.radius * Vector2d(std::cos(a), std::sin(a)));
    }
    add(f.end);
    // The straight edge to the next fillet.
    const Vector2d& next = fillets[(i + 1) % n].start;
    const int edge_pieces = pieces((next - f.end).norm(), max_edge, 1);
    for (int k = 1; k < edge_pieces; ++k) add(f.end + (next - f.end) * k / edge_pieces);
  }
  if ((outline.front() - outline.back()).norm() <= 1e-12) outline.pop_back();
  return outline;
}

/// Dzhanibekov's T-handle: a flat T with rounded corners, 80 mm across, 59 mm tall, 10 mm thick.
TriangleMesh t_handle() {
  const std::vector<Vector2d> corners = {
      {-0.006, -0.052}, {0.006, -0.052},  // foot of the stem
      {0.006, -0.007},  {0.040, -0.007},  // underside of the right arm
      {0.040, 0.007},   {-0.040, 0.007},  // top of the bar
      {-0.040, -0.007}, {-0.006, -0.007}};
  const std::vector<double> radii = {0.003, 0.003, 0.003, 0.0069, 0.0069, 0.0069, 0.0069, 0.003};
  TriangleMesh mesh =
      tumble::engine::extrude_polygon(rounded_outline(corners, radii, 0.0006), -0.005, 0.005);
  return mesh;
}

/// A tube of elliptical section (half-width `width` in the plane, half-depth `depth` along z)
/// swept along the ellipse of semi-axes `a` (x) and `b` (y) centred at `centre`.
TriangleMesh elliptic_ring(double a, double b, const Vector2d& centre, double width, double depth,
                           int around, int section) {
  TriangleMesh mesh;
  for (int i = 0; i < around; ++i) {
    const double t = 2.0 * kPi * i / around;
    const Vector2d point = centre + Vector2d(a * std::cos(t), b * std::sin(t));
    const Vector2d normal = Vector2d(b * std::cos(t), a * std::sin(t)).normalized();
    for (int j = 0; j < section; ++j) {
      const double s = 2.0 * kPi * j / section;
      const Vector2d in_plane = point + width * std::cos(s) * normal;
      mesh.positions.emplace_back(in_plane.x(), in_plane.y(), depth * std::sin(s));
    }
  }
  // Same parametrisation as a torus: d/dt x d/ds points out of the tube.
  auto vertex = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % around) * section + j % section);
  };
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < section; ++j) {
      mesh.triangles.push_back({vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)});
      mesh.triangles.push_back({vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)});
    }
  }
  return mesh;
}

/// A tennis racket along +y, 68 cm long: the head frame (an elliptic tube), the string bed (a
/// 1.5 mm plate filling the head with a 1 mm gap) and the handle with its open V throat (a
/// 22 mm thick profile whose arms stop 1 mm short of the frame). Three parts, none overlapping.
TriangleMesh tennis_racket() {
  const double a = 0.125, b = 0.16;            // head centreline semi-axes
  const double width = 0.0075, depth = 0.011;  // frame half-width (in plane) and half-depth
  const double gap = 0.001;
  const Vector2d centre(0.0, 0.68 - b - width);
  auto offset_point = [&](double t, double offset) {
    const Vector2d normal = Vector2d(b * std::cos(t), a * std::sin(t)).normalized();
    return Vector2d(centre + Vector2d(a * std::cos(t), b * std::sin(t)) + offset * normal);
  };

  TriangleMesh racket = elliptic_ring(a, b, centre, width, depth, 192, 16);

  // String bed: the frame's inner offset curve, pulled in by the gap.
  std::vector<Vector2d> bed;
  for (int k = 0; k < 128; ++k) bed.push_back(offset_point(2.0 * kPi * k / 128, -width - gap));
  tumble::engine::append_mesh(racket, tumble::engine::extrude_polygon(bed, -0.00075, 0.00075));

  // Handle and throat, counter-clockwise from the butt; the arms' tops follow the frame's outer
  // offset curve at the gap.
  const double half_grip = 0.013, grip_top = 0.20, spread = 0.55, arm = 0.22;
  const double butt = 0.004;  // radius of the butt's rounded corners
  std::vector<Vector2d> throat;
  for (int k = 0; k <= 6; ++k) {
    const double angle = kPi + 0.5 * kPi * k / 6;
    throat.emplace_back(-half_grip + butt + butt * std::cos(angle), butt + butt * std::sin(angle));
  }
  for (int k = 0; k <= 6; ++k) {
    const double angle = 1.5 * kPi + 0.5 * kPi * k / 6;
    throat.emplace_back(half_grip - butt + butt * std::cos(angle), butt + butt * std::sin(angle));
  }
  const int grip_pieces = 25;
  for (int k = 1; k <= grip_pieces; ++k) {
    throat.emplace_back(half_grip, butt + (grip_top - butt) * k / grip_pieces);
  }
  const int arc_pieces = 16;
  for (int k = 0; k <= arc_pieces; ++k) {
    throat.push_back(offset_point(-0.5 * kPi + spread - arm * k / arc_pieces, width + gap));
  }
  throat.emplace_back(0.0, 0.30);
  for (int k = 0; k <= arc_pieces; ++k) {
    throat.push_back(
        offset_point(-0.5 * kPi - spread + arm * (arc_pieces - k) / arc_pieces, width + gap));
  }
  for (int k = 0; k < grip_pieces; ++k) {
    throat.emplace_back(-half_grip, grip_top - (grip_top - butt) * k / grip_pieces);
  }
  tumble::engine::append_mesh(racket, tumble::engine::extrude_polygon(throat, -depth, depth));
  return racket;
}

/// A spinning top, 62 mm tall and 60 mm wide: a pointed tip at the origin, a curved flank up to
/// a rounded rim, a shallow conical top and a stem with a rounded end; axis z.
TriangleMesh spinning_top() {
  std::vector<Vector2d> profile = {{0.0, 0.0}};
  // Flank r = R (2u - u^2): pointed (slope 2.7) at the tip, vertical where it meets the rim.
  const int flank = 16;
  for (int k = 1; k <= flank; ++k) {
    const double u = static_cast<double>(k) / flank;
    profile.emplace_back(0.030 * (2.0 * u - u * u), 0.022 * u);
  }
  // Rim: a quarter circle of radius 4 mm.
  for (int k = 1; k <= 8; ++k) {
    const double angle = 0.5 * kPi * k / 8;
    profile.emplace_back(0.026 + 0.004 * std::cos(angle), 0.022 + 0.004 * std::sin(angle));
  }
  // Top face, fillet into the stem, the stem and its rounded end.
  profile.insert(profile.end(), {{0.016, 0.028},
                                 {0.0065, 0.0305},
                                 {0.0048, 0.0315},
                                 {0.0041, 0.033},
                                 {0.004, 0.035},
                                 {0.004, 0.045}});
  for (int k = 0; k < 8; ++k) {
    const double angle = 0.5 * kPi * k / 8;
    profile.emplace_back(0.004 * std::cos(angle), 0.058 + 0.004 * std::sin(angle));
  }
  profile.emplace_back(0.0, 0.062);
  return tumble::engine::revolve_profile(profile, 96);
}

/// A coin 24 mm across and 2 mm thick at its raised rim (1.8 mm in the field); axis z.
TriangleMesh coin() {
  return tumble::engine::revolve_profile({{0.0, -0.0009},
                                          {0.0106, -0.0009},
                                          {0.0109, -0.001},
                                          {0.0116, -0.001},
                                          {0.0119, -0.0008},
                                          {0.012, -0.0005},
                                          {0.012, 0.0005},
                                          {0.0119, 0.0008},
                                          {0.0116, 0.001},
                                          {0.0109, 0.001},
                                          {0.0106, 0.0009},
                                          {0.0, 0.0009}},
                                         160);
}

/// A rugby ball, 28 cm long and 19 cm across: the lens between two circular arcs, revolved
/// about its long axis z, with pointed ends.
TriangleMesh rugby_ball() {
  const double half_length = 0.14, equator = 0.095;
  // Arc through (0, +-half_length) and (equator, 0), centred on the r axis at -offset.
  const double offset = (half_length * half_length - equator * equator) / (2.0 * equator);
  const double radius = equator + offset;
  const double end_angle = std::asin(half_length / radius);
  std::vector<Vector2d> profile = {{0.0, -half_length}};
  const int steps = 48;
  for (int k = 1; k < steps; ++k) {
    const double angle = -end_angle + 2.0 * end_angle * k / steps;
    profile.emplace_back(radius * std::cos(angle) - offset, radius * std::sin(angle));
  }
  profile.emplace_back(0.0, half_length);
  return tumble::engine::revolve_profile(profile, 64);
}

/// A rubble-pile asteroid about 500 x 300 x 220 m: an icosphere stretched to an ellipsoid with
/// deterministic bumps and dents. Every vertex moves along its own ray from the centre by a
/// positive factor, so the surface stays star-shaped and therefore closed and non-intersecting.
TriangleMesh asteroid() {
  TriangleMesh mesh = tumble::engine::icosphere_mesh(1.0, 4);
  SplitMix64 random(20240607);
  struct Bump {
    Vector3d direction;
    double height, width;
  };
  std::vector<Bump> bumps;
  while (bumps.size() < 30) {
    const Vector3d d(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
    if (d.norm() > 1.0 || d.norm() < 0.1) continue;
    bumps.push_back({d.normalized(), random.uniform(-0.12, 0.12), random.uniform(0.02, 0.2)});
  }
  const Vector3d radii(250.0, 150.0, 110.0);
  for (auto& position : mesh.positions) {
    const Vector3d direction = position.normalized();
    double factor = 1.0 + random.uniform(-0.01, 0.01);  // fine gravel
    for (const Bump& bump : bumps) {
      factor += bump.height * std::exp(-(1.0 - direction.dot(bump.direction)) / bump.width);
    }
    position = radii.cwiseProduct(direction) * std::max(factor, 0.3);
  }
  return mesh;
}

/// Writes `mesh` as OBJ with a header naming the generator.
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& description) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
  out << "# " << path.filename().string() << ": " << description << "\n"
      << "# Generated by assets/tools/make_meshes.cpp (make_meshes OUTPUT_DIR); do not edit.\n"
      << "# Units: metres. " << mesh.positions.size() << " vertices, " << mesh.triangles.size()
      << " triangles, outward (counter-clockwise) winding.\n";
  std::array<char, 128> line{};
  for (const Vector3d& p : mesh.positions) {
    std::snprintf(line.data(), line.size(), "v %.9g %.9g %.9g\n", p.x(), p.y(), p.z());
    out << line.data();
  }
  for (const auto& t : mesh.triangles) {
    out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
  if (!out.flush()) throw std::runtime_error(path.string() + ": write failed");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_meshes OUTPUT_DIR\n");
    return 2;
  }
  try {
    const std::filesystem::path directory = argv[1];
    std::filesystem::create_directories(directory);
    struct Item {
      const char* file;
      const char* description;
      TriangleMesh (*make)();
    };
    const Item items[] = {
        {"t_handle.obj", "Dzhanibekov's T-handle, flat T 80 x 59 x 10 mm", t_handle},
        {"tennis_racket.obj", "tennis racket 68 cm long: frame, string bed, handle (3 parts)",
         tennis_racket},
        {"spinning_top.obj", "spinning top 60 mm wide, 62 mm tall, tip at the origin, axis z",
         spinning_top},
        {"coin.obj", "coin 24 mm across, 2 mm thick with a raised rim, axis z", coin},
        {"rugby_ball.obj", "rugby ball 28 cm long, 19 cm across, pointed ends, axis z", rugby_ball},
        {"asteroid.obj", "irregular asteroid about 500 x 300 x 220 m", asteroid},
    };
    for (const Item& item : items) {
      const TriangleMesh mesh = item.make();
      write_obj(directory / item.file, mesh, item.description);
      std::printf("%-18s %6zu vertices %6zu triangles\n", item.file, mesh.positions.size(),
                  mesh.triangles.size());
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "make_meshes: %s\n", error.what());
    return 1;
  }
  return 0;
}
