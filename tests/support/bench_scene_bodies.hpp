#pragma once
// The bodies of the scenes `tumble bench` is documented with (assets/scenes/t_handle_flip.json
// and assets/scenes/heavy_top.json) as the scenes compile them, written out as numbers so that
// the engine tests, which read no meshes, can run them. tests/app/scene/
// bench_scene_bodies_test.cpp checks these numbers against compile_scene of the two files.

#include <Eigen/Geometry>

#include "engine/body/rigid_body.hpp"

namespace tumble::testing {

/// A scene's one body, its initial state, and the scene's duration and dt.
struct BenchSceneBody {
  engine::BodyModel body;
  engine::BodyState initial;
  double duration = 0.0;  ///< s
  double dt = 0.0;        ///< s: the output step, and the bench's sampling interval
};

/// t_handle_flip.json: the T-handle mesh at 2700 kg/m^3 spun at (0.05, 10, 0.05) rad/s in its
/// principal axes (identity orientation), near its intermediate axis: torque-free, it flips
/// over and back again and again.
inline BenchSceneBody t_handle_flip_body() {
  BenchSceneBody scene;
  scene.body.name = "t-handle";
  scene.body.mass = 0.043711944308448047;
  scene.body.moments =
      Eigen::Vector3d(1.1556168534804133e-05, 1.5028538761214023e-05, 2.5856174923445304e-05);
  scene.initial = engine::spinning_state(scene.body, Eigen::Quaterniond::Identity(),
                                         Eigen::Vector3d(0.05, 10.0, 0.05));
  scene.duration = 20.0;
  scene.dt = 0.001;
  return scene;
}

/// heavy_top.json: the spinning-top mesh at 1000 kg/m^3 on its tip under gravity, spun at
/// 120 rad/s about its symmetry axis (principal axis 1), tilted 0.3 rad: a Lagrange top.
inline BenchSceneBody heavy_top_body() {
  BenchSceneBody scene;
  scene.body.name = "top";
  scene.body.mass = 0.049216232406255576;
  scene.body.moments =
      Eigen::Vector3d(1.6641722436323629e-05, 2.897755026320335e-05, 2.8977550263203354e-05);
  scene.body.pivoted = true;
  scene.body.pivot = Eigen::Vector3d(0.0, 0.0056024720790263383, -0.018111269160490391);
  scene.body.center_offset = Eigen::Vector3d(0.018958000000000003, 0.0, 0.0);
  scene.body.forces = {engine::Gravity{Eigen::Vector3d(0.0, 0.0, -9.81)}};
  const Eigen::Quaterniond orientation(0.69916673424638032, 0.10566871686195269,
                                       -0.69916673424638021, -0.10566871686195267);
  scene.initial = engine::spinning_state(scene.body, orientation, Eigen::Vector3d(120.0, 0.0, 0.0));
  engine::update_pivot_kinematics(scene.body, scene.initial);
  scene.duration = 10.0;
  scene.dt = 0.0002;
  return scene;
}

}  // namespace tumble::testing
