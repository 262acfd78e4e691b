// The box of equal inertia against its closed form: a uniform box's own inertia gives back its
// sides and axes.
#include "app/video/inertia_box.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace tumble::app {
namespace {

/// The inertia of a uniform box of `mass` and `sides` along the columns of `axes`:
/// axes diag(m/12 (b^2 + c^2), ...) axes^T.
Eigen::Matrix3d box_inertia(double mass, const Eigen::Vector3d& sides,
                            const Eigen::Matrix3d& axes) {
  const Eigen::Vector3d s2 = sides.cwiseAbs2();
  const Eigen::Vector3d moments =
      mass / 12.0 * Eigen::Vector3d(s2[1] + s2[2], s2[0] + s2[2], s2[0] + s2[1]);
  return axes * moments.asDiagonal() * axes.transpose();
}

TEST(EqualInertiaBox, ABoxsOwnInertiaGivesBackItsSidesAxesAndCentre) {
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
                                Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
  const Eigen::Vector3d sides(0.3, 0.2, 0.1);  // the longest side has the smallest moment
  const engine::MassProperties box{2.5, Eigen::Vector3d(0.1, -0.2, 0.3),
                                   box_inertia(2.5, sides, turn)};
  const InertiaBox found = equal_inertia_box(box);
  // Sides in the order of ascending principal moments: longest first.
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(found.sides[i], sides[i], 1e-12) << i;
  EXPECT_EQ(found.center, box.center_of_mass);
  // Each axis is the box's own, up to its sign; the frame is proper.
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::abs(found.axes.col(i).dot(turn.col(i))), 1.0, 1e-12) << i;
  }
  EXPECT_NEAR(found.axes.determinant(), 1.0, 1e-12);
  // And the box of those sides along those axes has the inertia it came from.
  EXPECT_LT((box_inertia(2.5, found.sides, found.axes) - box.inertia).norm(),
            1e-12 * box.inertia.norm());
}

TEST(EqualInertiaBox, ACubeAndAFlatPlate) {
  const engine::MassProperties cube{
      8.0, Eigen::Vector3d::Zero(),
      box_inertia(8.0, Eigen::Vector3d::Constant(0.5), Eigen::Matrix3d::Identity())};
  const InertiaBox cube_box = equal_inertia_box(cube);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(cube_box.sides[i], 0.5, 1e-12);

  // A plate of no thickness: I3 = I1 + I2, so its third side is zero (to rounding).
  const engine::MassProperties plate{
      1.0, Eigen::Vector3d::Zero(),
      box_inertia(1.0, Eigen::Vector3d(0.4, 0.2, 0.0), Eigen::Matrix3d::Identity())};
  const InertiaBox plate_box = equal_inertia_box(plate);
  EXPECT_NEAR(plate_box.sides[0], 0.4, 1e-12);
  EXPECT_NEAR(plate_box.sides[1], 0.2, 1e-12);
  EXPECT_LT(plate_box.sides[2], 1e-6);
}

TEST(EqualInertiaBox, AnImpossibleTensorGivesAZeroSideNotANan) {
  // I3 > I1 + I2 breaks the triangle inequality: 6 (I1 + I2 - I3) / m < 0.
  const engine::MassProperties impossible{1.0, Eigen::Vector3d::Zero(),
                                          Eigen::Vector3d(1.0, 1.0, 3.0).asDiagonal()};
  const InertiaBox box = equal_inertia_box(impossible);
  EXPECT_EQ(box.sides[2], 0.0);
  EXPECT_NEAR(box.sides[0], std::sqrt(6.0 * 3.0), 1e-12);
}

}  // namespace
}  // namespace tumble::app
