#pragma once
// MuJoCo as the independent check of the MJCF reader: each body's mass, centre of mass and
// principal moments as mj_loadXML compiles them, next to tumble's for the same file.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "app/robot/link_inertial.hpp"
#include "app/robot/robot_model.hpp"

namespace tumble::testing {

/// A body's inertial: mass, centre of mass in the body's frame, principal moments ascending.
struct BodyInertial {
  std::string name;
  double mass = 0.0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();
  /// About the centre of mass in the body's axes (MuJoCo: body_iquat turning body_inertia).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

inline Eigen::Vector3d sorted(Eigen::Vector3d v) {
  std::sort(v.data(), v.data() + 3);
  return v;
}

inline Eigen::Vector3d principal_moments(const Eigen::Matrix3d& inertia) {
  return sorted(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues());
}

/// Every body but the world, as MuJoCo compiles `file` (body ids 1, 2, ...). Throws
/// std::runtime_error with MuJoCo's message when it refuses the file.
inline std::vector<BodyInertial> mujoco_bodies(const std::filesystem::path& file) {
  // Warnings would otherwise go to MUJOCO_LOG.TXT in the working folder.
  mju_user_warning = [](const char*) {};
  char error[1000] = "";
  mjModel* model = mj_loadXML(file.c_str(), nullptr, error, sizeof error);
  if (!model) throw std::runtime_error("MuJoCo: " + file.string() + ": " + error);
  std::vector<BodyInertial> out;
  for (int b = 1; b < model->nbody; ++b) {
    BodyInertial body;
    const char* name = mj_id2name(model, mjOBJ_BODY, b);
    body.name = name ? name : "";
    body.mass = model->body_mass[b];
    body.center_of_mass = Eigen::Vector3d(model->body_ipos + 3 * b);
    const Eigen::Vector3d diagonal(model->body_inertia + 3 * b);
    body.moments = sorted(diagonal);
    const mjtNum* q = model->body_iquat + 4 * b;
    const Eigen::Matrix3d turn = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
    body.inertia = turn * diagonal.asDiagonal() * turn.transpose();
    out.push_back(body);
  }
  mj_deleteModel(model);
  return out;
}

/// Each link's inertial as tumble computes it from the geometry (the geoms' own densities and
/// masses, 1000 kg/m^3 where a geom gives none), unset for a link it leaves alone.
inline std::vector<std::optional<engine::MassProperties>> tumble_inertials(
    const app::robot::Robot& robot) {
  std::vector<std::optional<engine::MassProperties>> out;
  for (const app::robot::Link& link : robot.links) {
    const app::robot::LinkInertial inertial = app::robot::compute_link_inertial(link, {});
    if (inertial.error) throw std::runtime_error(*inertial.error);
    out.push_back(inertial.computed);
  }
  return out;
}

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

/// The largest relative differences seen between tumble and MuJoCo, over all bodies compared:
/// mass and moments relative to themselves, the centre of mass relative to `length` (m), the
/// inertia tensor in the body's axes relative to its norm (this one sees the orientations).
struct Agreement {
  double mass = 0.0;
  double center_of_mass = 0.0;
  double moments = 0.0;
  double tensor = 0.0;

  void add(const BodyInertial& mujoco, const engine::MassProperties& tumble, double length) {
    mass = std::max(mass, std::abs(tumble.mass - mujoco.mass) / mujoco.mass);
    center_of_mass =
        std::max(center_of_mass, (tumble.center_of_mass - mujoco.center_of_mass).norm() / length);
    const Eigen::Vector3d ours = principal_moments(tumble.inertia);
    moments = std::max(moments, ((ours - mujoco.moments).cwiseAbs().array() /
                                 mujoco.moments.cwiseAbs().array().max(1e-300))
                                    .maxCoeff());
    tensor = std::max(tensor, (tumble.inertia - mujoco.inertia).norm() / mujoco.inertia.norm());
  }
  std::string text() const {
    char buffer[200];
    std::snprintf(buffer, sizeof buffer,
                  "mass %.1e, centre of mass %.1e, principal moments %.1e, tensor %.1e", mass,
                  center_of_mass, moments, tensor);
    return buffer;
  }
};

/// Prints the agreement (docs/inertials.md's table quotes these lines) and expects mass, centre of
/// mass and moments within `tolerance`, the tensor in the body's axes within
/// `tensor_tolerance` (MuJoCo's own eigen decomposition limits it to about 1e-7).
inline void expect_agreement(const Agreement& agreement, const std::string& what, double tolerance,
                             double tensor_tolerance) {
  std::cout << "[ MuJoCo   ] " << what << ": largest relative difference " << agreement.text()
            << "\n";
  EXPECT_LT(agreement.mass, tolerance) << what;
  EXPECT_LT(agreement.center_of_mass, tolerance) << what;
  EXPECT_LT(agreement.moments, tolerance) << what;
  EXPECT_LT(agreement.tensor, tensor_tolerance) << what;
}

}  // namespace tumble::testing
