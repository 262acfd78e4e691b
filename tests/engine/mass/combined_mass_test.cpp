// Mass properties of bodies held together (engine::combined) against the mesh of the whole.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>
#include <vector>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/mass_properties.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "inertia_expectations.hpp"

namespace tumble::engine {
namespace {

MassProperties of_mesh(const TriangleMesh& mesh) {
  MassOptions options;
  options.density = 1000.0;
  return analyze_mesh(mesh, options, "combined test").mass_properties;
}

TriangleMesh placed_box(const Eigen::Vector3d& size, const Eigen::Matrix3d& rotation,
                        const Eigen::Vector3d& offset) {
  TriangleMesh box = box_mesh(size);
  transform_mesh(box, rotation, offset);
  return box;
}

// Two disjoint boxes, turned and moved: the sum of their parts is the mesh of both at once.
TEST(CombinedMass, TwoBoxesEqualTheMeshOfBoth) {
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  const TriangleMesh a = placed_box({0.2, 0.3, 0.5}, turn, {1.0, -2.0, 0.5});
  const TriangleMesh b = placed_box({0.6, 0.1, 0.1}, Eigen::Matrix3d::Identity(), {-1.0, 0.5, 3});
  TriangleMesh both = a;
  append_mesh(both, b);

  const MassProperties whole = of_mesh(both);
  const MassProperties sum = combined({of_mesh(a), of_mesh(b)});
  EXPECT_NEAR(sum.mass, whole.mass, 1e-12 * whole.mass);
  testing::expect_vector_near(sum.center_of_mass, whole.center_of_mass, 1e-12);
  testing::expect_inertia_near(sum.inertia, whole.inertia, 1e-11);
}

// A single part is itself; the closed form of two point-like masses on a line.
TEST(CombinedMass, ParallelAxisClosedForm) {
  MassProperties unit;
  unit.mass = 2.0;
  unit.inertia = Eigen::Matrix3d::Identity() * 0.1;
  const MassProperties one = combined({unit.translated({1.0, 2.0, 3.0})});
  testing::expect_vector_near(one.center_of_mass, Eigen::Vector3d(1.0, 2.0, 3.0), 0.0);
  testing::expect_inertia_near(one.inertia, unit.inertia, 0.0);

  // Masses 2 and 2 at x = -1 and x = +1: I_yy = I_zz = 0.2 + 4 * 1^2, I_xx = 0.2.
  const MassProperties pair =
      combined({unit.translated({-1.0, 0.0, 0.0}), unit.translated({1.0, 0.0, 0.0})});
  EXPECT_DOUBLE_EQ(pair.mass, 4.0);
  testing::expect_vector_near(pair.center_of_mass, Eigen::Vector3d::Zero(), 0.0);
  testing::expect_inertia_near(pair.inertia, Eigen::Vector3d(0.2, 4.2, 4.2).asDiagonal(), 1e-15);
}

TEST(CombinedMass, NothingOrNoMassIsABug) {
  EXPECT_THROW(combined({}), std::invalid_argument);
  EXPECT_THROW(combined({MassProperties{}}), std::invalid_argument);
}

}  // namespace
}  // namespace tumble::engine
