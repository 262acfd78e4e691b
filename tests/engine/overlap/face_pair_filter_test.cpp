// The overlap checks' fast paths (engine/overlap/src/face_pairs.hpp: region certificates, the
// certified floating-point filter, the grid, the threads) against the exact predicates alone
// (FacePairMethod::kExact) and CGAL's box intersection with exact predicates for every pair
// (kReference): on near-degenerate meshes, where the filter must defer to the exact path, and
// on randomly perturbed ones, every method gives the same findings, face pair counts included.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>

#include "engine/geometry/mesh_topology.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/overlap/part_overlap.hpp"

namespace tumble::engine::detail {
namespace {

using ::testing::HasSubstr;

/// The axis-aligned box [low, high] with exactly these coordinates, outward.
TriangleMesh exact_box(const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  TriangleMesh mesh = box_mesh(Eigen::Vector3d::Ones());  // corners at +-0.5
  for (Eigen::Vector3d& p : mesh.positions) {
    for (int axis = 0; axis < 3; ++axis) p[axis] = p[axis] < 0.0 ? low[axis] : high[axis];
  }
  return mesh;
}

TriangleMesh joined_meshes(TriangleMesh a, const TriangleMesh& b) {
  append_mesh(a, b);
  return a;
}

PartOverlaps overlaps_of(const TriangleMesh& mesh, FacePairMethod method, unsigned threads) {
  const Topology topology = analyze_topology(mesh);
  EXPECT_TRUE(topology.closed());
  OverlapOptions options;
  options.method = method;
  options.threads = threads;
  return find_part_overlaps(mesh, topology.triangle_part, topology.parts, options);
}

/// The verdicts as text (a mismatch prints both).
std::string described(const PartOverlaps& overlaps) {
  std::ostringstream out;
  out.precision(17);
  for (const OverlapFinding& f : overlaps.findings) {
    out << "finding kind " << static_cast<int>(f.kind) << " parts " << f.first << ' ' << f.second
        << " pairs " << f.face_pairs << " volume "
        << (f.shared_volume ? std::to_string(*f.shared_volume) : "none") << " cavity " << f.cavity
        << " approximate " << f.approximate << '\n';
  }
  for (const PartNesting& n : overlaps.nesting) {
    out << "nesting " << n.inner << " in " << n.outer << " winding " << n.winding << '\n';
  }
  return out.str();
}

constexpr FacePairMethod kFastMethods[] = {FacePairMethod::kExact, FacePairMethod::kFiltered,
                                           FacePairMethod::kCertified};

/// Checks that every method, on one thread and on four, gives the reference's verdicts; returns
/// those verdicts.
std::string same_verdicts(const TriangleMesh& mesh) {
  const std::string expected = described(overlaps_of(mesh, FacePairMethod::kReference, 1));
  for (const FacePairMethod method : kFastMethods) {
    for (const unsigned threads : {1u, 4u}) {
      EXPECT_EQ(described(overlaps_of(mesh, method, threads)), expected)
          << "method " << static_cast<int>(method) << ", " << threads << " threads";
    }
  }
  return expected;
}

const double kBelowOne = std::nextafter(1.0, 0.0);
const double kAboveOne = std::nextafter(1.0, 2.0);

TEST(FacePairFilter, BoxesTouchingWithinOneUlp) {
  // The unit cube and a smaller box against its face x = 1, coplanar with it there: touching
  // at x = 1, one ulp into the cube (they cross, a sliver of volume 2^-53 * 0.25), one ulp
  // away (apart).
  const TriangleMesh cube = exact_box({0, 0, 0}, {1, 1, 1});
  const auto against = [&](double x) {
    return joined_meshes(cube, exact_box({x, 0.25, 0.25}, {x + 1, 0.75, 0.75}));
  };
  EXPECT_EQ(same_verdicts(against(1.0)), "");
  EXPECT_THAT(same_verdicts(against(kBelowOne)), HasSubstr("finding kind 3 parts 0 1"));
  EXPECT_EQ(same_verdicts(against(kAboveOne)), "");
  // The filter cannot decide the touching faces: the exact predicates do.
  EXPECT_GT(overlaps_of(against(1.0), FacePairMethod::kFiltered, 1).stats.deferred, 0u);
}

TEST(FacePairFilter, CoplanarFacesOverlappingOrOnlySharingAnEdge) {
  // Two cubes side by side sharing the plane x = 1 over a 0.5 x 0.5 patch (coplanar overlap),
  // and two sharing only the edge line x = 1, y = 1 (the second shifted diagonally).
  const TriangleMesh cube = exact_box({0, 0, 0}, {1, 1, 1});
  EXPECT_EQ(same_verdicts(joined_meshes(cube, exact_box({1, 0.5, 0.5}, {2, 1.5, 1.5}))), "");
  EXPECT_EQ(same_verdicts(joined_meshes(cube, exact_box({1, 1, 0}, {2, 2, 1}))), "");
  EXPECT_EQ(same_verdicts(joined_meshes(cube, exact_box({1, 1, 1}, {2, 2, 2}))), "");
  // One ulp further in along y, the edge contact becomes a face contact: still touching.
  EXPECT_EQ(same_verdicts(joined_meshes(cube, exact_box({1, kBelowOne, 0}, {2, 2, 1}))), "");
  // One ulp in along both x and y, their surfaces cross (a prism of 2^-106 m^2 section, too
  // thin for CGAL's Boolean: the finding says so, kUndecided, rather than "touch").
  EXPECT_THAT(same_verdicts(joined_meshes(cube, exact_box({kBelowOne, kBelowOne, 0}, {2, 2, 1}))),
              HasSubstr("finding kind 4 parts 0 1"));
}

TEST(FacePairFilter, SliverFacesNearlyCollinear) {
  // A tetrahedron whose apex lies one ulp off the plane of the base edge x = 0..1 (a sliver of
  // two nearly collinear faces), beside the cube and a copy of itself one ulp through the cube.
  const double tiny = std::numeric_limits<double>::denorm_min() * 0x1p60;  // 2^-1014
  for (const double lift : {tiny, 0x1p-52, 0x1p-30}) {
    const TriangleMesh sliver =
        tetrahedron_mesh({Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(2, 0, 0),
                          Eigen::Vector3d(1.5, lift, 0), Eigen::Vector3d(1.5, 0, 1)});
    const TriangleMesh cube = exact_box({0, -1, 0}, {1, 1, 1});
    same_verdicts(joined_meshes(cube, sliver));
    TriangleMesh through = sliver;
    for (Eigen::Vector3d& p : through.positions) p.x() = p.x() == 1.0 ? kBelowOne : p.x();
    EXPECT_THAT(same_verdicts(joined_meshes(cube, through)), HasSubstr("parts 0 1"));
  }
}

TEST(FacePairFilter, FacesSharingAVertexThatCross) {
  // A box and a tetrahedron sharing the box's corner (2, 2, 2): one part, whose tetrahedron
  // reaches into the box through its top face, so faces sharing that vertex cross.
  const TriangleMesh fused =
      joined_meshes(exact_box({0, 0, 0}, {2, 2, 2}),
                    tetrahedron_mesh({Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(0.5, 1, 3),
                                      Eigen::Vector3d(1, 0.5, 3), Eigen::Vector3d(1, 1, 1)}));
  TriangleMesh welded = fused;
  weld_by_position(welded);
  EXPECT_THAT(same_verdicts(welded), HasSubstr("finding kind 0 parts 0 0"));
  // The tetrahedron's inner corner moved onto the box's top face, then one ulp above it: its
  // faces only touch the box's (no crossing) or stay outside.
  for (const double z : {2.0, std::nextafter(2.0, 3.0)}) {
    TriangleMesh moved = welded;
    for (Eigen::Vector3d& p : moved.positions) {
      if (p == Eigen::Vector3d(1, 1, 1)) p = Eigen::Vector3d(1, 1, z);
    }
    EXPECT_EQ(same_verdicts(moved), "") << "z = " << z;
  }
}

/// A welded icosphere (subdivisions 3, 1280 faces) of radius 1 at `centre`, each vertex moved
/// by up to `noise` along each axis, then (if `lattice` > 0) rounded to multiples of 1 /
/// lattice (exact coplanarities and collinearities), re-welded without faces that lost area.
TriangleMesh perturbed_ball(std::mt19937& random, const Eigen::Vector3d& centre, double noise,
                            double lattice) {
  TriangleMesh mesh = icosphere_mesh(1.0, 3);
  std::uniform_real_distribution<double> shift(-noise, noise);
  for (Eigen::Vector3d& p : mesh.positions) {
    p += centre + Eigen::Vector3d(shift(random), shift(random), shift(random));
    if (lattice > 0.0) p = (p * lattice).array().round().matrix() / lattice;
  }
  weld_by_position(mesh);
  remove_degenerate_triangles(mesh);
  remove_unreferenced_vertices(mesh);
  return mesh;
}

TEST(FacePairFilter, RandomlyPerturbedBallsGiveTheExactVerdicts) {
  std::mt19937 random(27);
  std::size_t crossing = 0, deferred = 0;
  for (int trial = 0; trial < 24; ++trial) {
    // Noise from none to several edge lengths (0.1): from smooth to badly tangled; some
    // snapped to a lattice; a second ball overlapping, touching or apart.
    const double noise = trial % 4 == 0 ? 0.0 : 0.002 * std::pow(2.0, trial % 6);
    const double lattice = trial % 3 == 0 ? 32.0 : 0.0;
    TriangleMesh mesh = perturbed_ball(random, Eigen::Vector3d::Zero(), noise, lattice);
    if (trial % 2 == 1) {
      const double gap = trial % 8 == 1 ? 2.0 : 1.5 + 0.25 * (trial % 5);
      append_mesh(mesh, perturbed_ball(random, Eigen::Vector3d(gap, 0, 0), noise, lattice));
    }
    const std::string verdicts = same_verdicts(mesh);
    crossing += verdicts.empty() ? 0 : 1;
    deferred += overlaps_of(mesh, FacePairMethod::kFiltered, 1).stats.deferred;
  }
  // The trials reach both clean and overlapping meshes, and the exact path.
  EXPECT_GT(crossing, 4u);
  EXPECT_LT(crossing, 24u);
  EXPECT_GT(deferred, 0u);
}

TEST(FacePairFilter, ThreadsAndCertificatesOnALargerTangledTorus) {
  // 40,000 faces (enough for four threads): a torus untouched, then with a band of vertices
  // pushed across the hole into the tube on the other side (crossings).
  TriangleMesh torus = torus_mesh(1.0, 0.3, 200, 100);
  EXPECT_EQ(same_verdicts(torus), "");
  const PartOverlaps clean = overlaps_of(torus, FacePairMethod::kCertified, 4);
  EXPECT_GT(clean.stats.regions, 0u);
  // Most regions are certified whole (not those holding too curved a piece of the tube).
  EXPECT_GT(2 * clean.stats.certified, clean.stats.regions);
  for (Eigen::Vector3d& p : torus.positions) {
    if (p.x() > 0.9 && std::abs(p.y()) < 0.05) p.x() -= 2.0;
  }
  EXPECT_THAT(same_verdicts(torus), HasSubstr("finding kind 0 parts 0 0"));
}

TEST(FacePairFilter, GivenBoundsChangeNothingEvenWhenTheyMissAVertex) {
  // The vertices' box given by the caller (as mesh_analysis gives it) saves a pass; a box that
  // misses a vertex (a caller's mistake) must not put a vertex in a cell outside the table. The
  // same verdicts and the same certified regions either way, clean and tangled.
  TriangleMesh torus = torus_mesh(1.0, 0.3, 200, 100);
  for (int tangled = 0; tangled < 2; ++tangled) {
    if (tangled == 1) {
      for (Eigen::Vector3d& p : torus.positions) {
        if (p.x() > 0.9 && std::abs(p.y()) < 0.05) p.x() -= 2.0;
      }
    }
    const Topology topology = analyze_topology(torus);
    Eigen::Vector3d low = torus.positions.front(), high = low;
    for (const Eigen::Vector3d& p : torus.positions) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    const Eigen::Vector3d middle = 0.5 * (low + high);
    using Box = std::pair<Eigen::Vector3d, Eigen::Vector3d>;
    const std::optional<Box> boxes[] = {std::nullopt, Box{low, high},
                                        Box{low.array() - 0.5, high.array() + 0.5},
                                        Box{middle, high}, Box{low, middle}};
    std::string first;
    FacePairStats first_stats;
    for (const std::optional<Box>& box : boxes) {
      OverlapOptions options;
      options.threads = 2;
      options.bounds = box;
      const PartOverlaps found =
          find_part_overlaps(torus, topology.triangle_part, topology.parts, options);
      if (!box) {
        first = described(found);
        first_stats = found.stats;
        continue;
      }
      EXPECT_EQ(described(found), first) << "tangled " << tangled;
      EXPECT_EQ(found.stats.regions, first_stats.regions) << "tangled " << tangled;
      EXPECT_EQ(found.stats.certified, first_stats.certified) << "tangled " << tangled;
      EXPECT_EQ(found.stats.candidates, first_stats.candidates) << "tangled " << tangled;
    }
    EXPECT_GT(first_stats.certified, 0u);
    EXPECT_EQ(first.empty(), tangled == 0);
  }
}

}  // namespace
}  // namespace tumble::engine::detail
