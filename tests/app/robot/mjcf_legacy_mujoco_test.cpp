// The legacy inertia method against MuJoCo itself: libmujoco 2.2.2 compiles meshes with its
// legacy approximation by default (exactmeshinertia="false"), so the same mesh files through
// mj_loadXML give the body masses, centres of mass and principal moments that tumble's
// --inertia legacy (or <mesh inertia="legacy">) must reproduce to rounding: an L-prism (3.41565
// of exact's 3 m^3), the same scaled and turned, a convex prism and a turned box off the grid of
// floats. Against exact: the box agrees (a box is its own box of equal inertia), the others do
// not, by the ratio of their box of equal inertia's volume to their own.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

#include <unistd.h>

#include "app/robot/mujoco_oracle.hpp"
#include "app/support/text_file.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/primitive_shapes.hpp"
#include "support/l_prism.hpp"
#include "support/stl_writer.hpp"

namespace tumble::app::robot {
namespace {

/// Mass, centre of mass and moments to double rounding (measured: 1.4e-15, 2.3e-16, 2.6e-15):
/// tumble rounds to float where MuJoCo's arithmetic does. The tensor in the body's axes only to
/// MuJoCo's eigen decomposition (measured 1.8e-9; mjcf_mujoco_test.cpp).
constexpr double kLegacyTolerance = 1e-12;
constexpr double kLegacyTensorTolerance = 1e-7;

/// `mesh` turned and moved off the origin: no coordinate is a round float.
engine::TriangleMesh legacy_turned(engine::TriangleMesh mesh) {
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(-1, 2, 0.5).normalized()).toRotationMatrix();
  for (Eigen::Vector3d& p : mesh.positions) p = turn * p + Eigen::Vector3d(0.13, -0.07, 0.21);
  return mesh;
}

/// MuJoCo 2.2.2's reading (its schema has no <mesh inertia>): every mesh legacy by default.
/// MESH_INERTIA is empty for MuJoCo and ` inertia="legacy"` for tumble's MuJoCo 3 reading.
const char* const kLegacyModel = R"(<mujoco model="legacy">
  <compiler meshdir="meshes"/>
  <asset>
    <mesh file="l.stl"MESH_INERTIA/>
    <mesh name="scaled_l" file="l.stl" scale="0.5 0.25 2"MESH_INERTIA/>
    <mesh file="prism.stl"MESH_INERTIA/>
    <mesh file="box.stl"MESH_INERTIA/>
  </asset>
  <worldbody>
    <body name="l" pos="0.3 0 0"><geom type="mesh" mesh="l" density="1"/></body>
    <body name="turned_l">
      <geom type="mesh" mesh="scaled_l" pos="0.1 -0.2 0.05" euler="30 -20 45" density="2700"/>
    </body>
    <body name="prism"><geom type="mesh" mesh="prism" density="2000"/></body>
    <body name="box"><geom type="mesh" mesh="box" density="500" pos="0 0.1 0"/></body>
    <body name="weighed_prism"><geom type="mesh" mesh="prism" mass="0.8"/></body>
  </worldbody>
</mujoco>
)";

std::string legacy_model(const std::string& mesh_inertia) {
  std::string text = kLegacyModel;
  for (std::size_t at; (at = text.find("MESH_INERTIA")) != std::string::npos;) {
    text.replace(at, 12, mesh_inertia);
  }
  return text;
}

class MjcfLegacyAgainstMujoco : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = std::filesystem::temp_directory_path() /
              ("tumble_legacy_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(folder_ / "meshes");
    tumble::testing::write_binary_stl(folder_ / "meshes" / "l.stl", tumble::testing::l_prism());
    tumble::testing::write_binary_stl(
        folder_ / "meshes" / "prism.stl",
        legacy_turned(engine::tessellate(engine::Cylinder{0.07, 0.15}, 20)));
    tumble::testing::write_binary_stl(folder_ / "meshes" / "box.stl",
                                      legacy_turned(engine::box_mesh({0.1, 0.06, 0.17})));
    tumble::testing::write_text(folder_ / "mujoco.xml", legacy_model(""));
    tumble::testing::write_text(folder_ / "tumble.xml", legacy_model(R"( inertia="legacy")"));
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  /// Each body's inertial as tumble computes `file` with `method` for the meshes that name none.
  std::vector<engine::MassProperties> ours(const std::string& file,
                                           engine::InertiaMethod method) const {
    const std::filesystem::path path = folder_ / file;
    const Robot robot = read_mjcf(path, read_text_file(path, "robot file"), {});
    ComputeOptions options;
    options.inertia = method;
    std::vector<engine::MassProperties> out;
    for (const Link& link : robot.links) {
      const LinkInertial inertial = compute_link_inertial(link, options);
      EXPECT_FALSE(inertial.error) << inertial.error.value_or("");
      EXPECT_EQ(methods_text(inertial.methods),
                file == "tumble.xml" ? "legacy" : engine::inertia_method_name(method))
          << link.name;
      out.push_back(inertial.computed.value_or(engine::MassProperties{}));
    }
    return out;
  }

  std::filesystem::path folder_;
};

TEST_F(MjcfLegacyAgainstMujoco, LegacyGivesMujocosInertials) {
  const std::vector<tumble::testing::BodyInertial> mujoco =
      tumble::testing::mujoco_bodies(folder_ / "mujoco.xml");
  ASSERT_EQ(mujoco.size(), 5u);
  // The measured approximation: 13.9% more than the L's 3 m^3 at density 1.
  EXPECT_NEAR(mujoco[0].mass, 3.41565, 1e-5);
  for (const auto& [file, method] :
       {std::pair<std::string, engine::InertiaMethod>{"mujoco.xml", engine::InertiaMethod::legacy},
        {"tumble.xml", engine::InertiaMethod::exact}}) {
    // tumble.xml asks for legacy in each <mesh>, which wins over the method given.
    const std::vector<engine::MassProperties> tumble = ours(file, method);
    ASSERT_EQ(tumble.size(), mujoco.size());
    tumble::testing::Agreement agreement;
    for (std::size_t i = 0; i < tumble.size(); ++i) agreement.add(mujoco[i], tumble[i], 1.0);
    tumble::testing::expect_agreement(agreement, "legacy mesh inertia, " + file, kLegacyTolerance,
                                      kLegacyTensorTolerance);
  }
}

/// The volume of the uniform box whose inertia is `exact`'s (mass `mass`, volume `volume`):
/// second moments c_i = (e_j + e_k - e_i) / 2 per unit density, half sizes sqrt(3 c_i / V).
double equal_inertia_box(const engine::MassProperties& exact, double volume) {
  const Eigen::Vector3d e = tumble::testing::principal_moments(exact.inertia);
  const double density = exact.mass / volume;
  double box = 8.0;
  for (int i = 0; i < 3; ++i) {
    const double c = (e.sum() - 2 * e[i]) / 2 / density;
    box *= std::sqrt(3 * c / volume);
  }
  return box;
}

TEST_F(MjcfLegacyAgainstMujoco, ExactAgreesOnlyOnTheBox) {
  const std::vector<engine::MassProperties> exact =
      ours("mujoco.xml", engine::InertiaMethod::exact);
  const std::vector<engine::MassProperties> legacy =
      ours("mujoco.xml", engine::InertiaMethod::legacy);
  ASSERT_EQ(exact.size(), 5u);
  // The L: 3 m^3 exact, 13.855% more in legacy, which is the box of equal inertia's volume.
  EXPECT_NEAR(exact[0].mass, 3.0, 1e-12);
  EXPECT_NEAR(legacy[0].mass / exact[0].mass - 1.0, 0.13855, 1e-5);
  EXPECT_NEAR(legacy[0].mass, equal_inertia_box(exact[0], 3.0), 1e-6);
  // The prism at 2000 kg/m^3: a box of equal inertia of another volume (float rounding: 1e-6).
  const double prism_volume = exact[2].mass / 2000;
  const double prism_box = equal_inertia_box(exact[2], prism_volume);
  EXPECT_NEAR(legacy[2].mass, 2000 * prism_box, 1e-6 * legacy[2].mass);
  EXPECT_GT(std::abs(prism_box / prism_volume - 1), 0.01);
  std::cout << "[ MuJoCo   ] legacy prism: " << 100 * (prism_box / prism_volume - 1)
            << "% of exact's mass\n";
  // The box: legacy is exact (to the float rounding of MuJoCo's vertices).
  EXPECT_NEAR(legacy[3].mass, exact[3].mass, 1e-6 * exact[3].mass);
  // A given mass: the same distribution as exact's, whatever the volume.
  const Eigen::Vector3d exact_moments = tumble::testing::principal_moments(exact[4].inertia);
  const Eigen::Vector3d legacy_moments = tumble::testing::principal_moments(legacy[4].inertia);
  EXPECT_LT((legacy_moments - exact_moments).cwiseAbs().maxCoeff(),
            1e-6 * exact_moments.maxCoeff());
  EXPECT_LT((legacy[4].center_of_mass - exact[4].center_of_mass).norm(), 1e-7);
}

}  // namespace
}  // namespace tumble::app::robot
