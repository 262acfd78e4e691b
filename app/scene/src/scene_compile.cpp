// Scene compilation: SceneDescription -> engine bodies, states and settings (the parsing is
// in scene.cpp).
#include "app/scene/scene.hpp"

#include <optional>
#include <string>
#include <utility>

#include "app/scene/mesh_inspection.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/mass/principal_frame.hpp"

namespace tumble::app {

engine::SimulationSettings simulation_settings(const SceneDescription& scene) {
  engine::SimulationSettings settings;
  settings.integrator = engine::integrator_from_name(scene.integrator).value();
  settings.dt = scene.dt;
  settings.duration = scene.duration;
  if (scene.tolerance) settings.tolerance = *scene.tolerance;
  if (scene.absolute_tolerance) settings.absolute_tolerance = *scene.absolute_tolerance;
  return settings;
}

namespace {

using tumble::InputError;

/// A body's mass and inertia about its centre of mass (body frame: a mesh's own axes), with
/// the principal frame of its mesh, if it has one.
struct BodyMatter {
  double mass = 0.0;
  Eigen::Matrix3d inertia_com;
  std::optional<engine::PrincipalFrame> mesh_principal;
};

/// Inspects a body's mesh; `shape`, when given, receives its triangles in the body frame: the
/// file's axes, scaled, with the centre of mass at the origin, outward as it was integrated.
engine::MeshReport import_body_mesh(const BodyDescription& body, const std::string& where,
                                    engine::TriangleMesh* shape) {
  engine::MassOptions options;
  options.mass = body.mass;
  options.density = body.density;
  options.scale = Eigen::Vector3d::Constant(body.scale);
  options.overlap = body.overlap;
  options.inertia = body.inertia_method;
  engine::MeshReport report;
  try {
    report = inspect_file(*body.mesh, options, shape);
  } catch (const InputError& error) {
    throw InputError(where + ".mesh: " + error.what());
  }
  if (shape) {
    for (Eigen::Vector3d& p : shape->positions) {
      p = p * body.scale - report.mass_properties.center_of_mass;
    }
    if (report.flipped) {
      for (auto& t : shape->triangles) std::swap(t[1], t[2]);
    }
  }
  return report;
}

/// A shape body's matter from the closed forms (engine/PHYSICS.md §9): the body frame is the
/// shape's own, whose origin is its centre of mass; its tessellation is kept when asked for.
BodyMatter shape_matter(const BodyDescription& body, std::size_t index, const std::string& where,
                        bool keep_geometry, CompiledScene& out) {
  const engine::Shape& shape = *body.shape;
  BodyMatter matter;
  try {
    const engine::MassProperties properties =
        body.mass ? engine::mass_properties_of_mass(shape, *body.mass)
                  : engine::mass_properties(shape, body.density.value());
    matter.mass = properties.mass;
    matter.inertia_com = properties.inertia;
    if (keep_geometry) out.geometry[index] = engine::tessellate(shape, kShapeSegments);
  } catch (const InputError& error) {
    throw InputError(where + ".shape: " + error.what());
  }
  return matter;
}

/// The body's matter, from its mesh (kept in `out` at `index`: report, and geometry when
/// asked for), its shape or its given inertia.
BodyMatter body_matter(const BodyDescription& body, std::size_t index, const std::string& where,
                       bool keep_geometry, CompiledScene& out) {
  if (body.shape) return shape_matter(body, index, where, keep_geometry, out);
  BodyMatter matter;
  if (!body.mesh) {
    matter.mass = body.mass.value();
    matter.inertia_com = body.inertia_tensor
                             ? *body.inertia_tensor
                             : Eigen::Matrix3d(body.principal_moments->asDiagonal());
    return matter;
  }
  engine::TriangleMesh shape;
  engine::MeshReport report = import_body_mesh(body, where, keep_geometry ? &shape : nullptr);
  ++out.meshes_imported;
  if (keep_geometry) out.geometry[index] = std::move(shape);
  matter.mass = report.mass_properties.mass;
  matter.inertia_com = report.mass_properties.inertia;
  matter.mesh_principal = report.principal;
  out.reports[index] = std::move(report);
  return matter;
}

/// The principal frame of the inertia about the rotation centre. A free mesh body keeps the
/// report's frame; a diagonal, ascending inertia keeps the user's.
engine::PrincipalFrame rotation_principal_frame(const Eigen::Matrix3d& inertia,
                                                const BodyMatter& matter, bool pivoted) {
  engine::PrincipalFrame frame;
  const Eigen::Vector3d diagonal = inertia.diagonal();
  if (matter.mesh_principal && !pivoted) {
    frame = *matter.mesh_principal;
  } else if (inertia.isDiagonal(0.0) && diagonal[0] <= diagonal[1] && diagonal[1] <= diagonal[2]) {
    frame.moments = diagonal;
    frame.axes.setIdentity();
  } else {
    frame = engine::principal_frame(inertia);
  }
  return frame;
}

/// Force terms: only those the scene asks for. `centre` is the rotation centre (body frame).
void add_forces(const SceneDescription& scene, const BodyDescription& body,
                const Eigen::Vector3d& centre, const Eigen::Matrix3d& body_to_principal,
                engine::BodyModel& model) {
  if (scene.gravity) model.forces.emplace_back(engine::Gravity{*scene.gravity});
  if (body.torque) {
    engine::ConstantTorque torque;
    torque.body_frame = body.torque_frame == VectorFrame::kBody;
    torque.torque =
        torque.body_frame ? Eigen::Vector3d(body_to_principal * *body.torque) : *body.torque;
    model.forces.emplace_back(torque);
  }
  if (body.spring) {
    engine::Spring spring;
    spring.anchor = body.spring->anchor;
    spring.attach = body_to_principal * (body.spring->attach - centre);
    spring.stiffness = body.spring->stiffness;
    spring.damping = body.spring->damping;
    model.forces.emplace_back(spring);
  }
}

/// Initial state: principal orientation, world L = R J R^T w about the rotation centre.
engine::BodyState initial_state(const BodyDescription& body, const engine::BodyModel& model) {
  engine::BodyState state;
  state.position = body.position;
  state.velocity = body.velocity.value_or(Eigen::Vector3d::Zero());
  state.orientation = (body.orientation * model.principal_to_body).normalized();
  const Eigen::Vector3d omega_world =
      body.angular_velocity_frame == VectorFrame::kBody
          ? Eigen::Vector3d(body.orientation * body.angular_velocity)
          : body.angular_velocity;
  const Eigen::Matrix3d rotation = state.orientation.toRotationMatrix();
  state.angular_momentum =
      rotation * (model.moments.asDiagonal() * (rotation.transpose() * omega_world));
  if (model.pivoted) engine::update_pivot_kinematics(model, state);
  return state;
}

/// Compiles bodies[index] of the scene into `out`.
void compile_body(const SceneDescription& scene, std::size_t index, bool keep_geometry,
                  CompiledScene& out) {
  const BodyDescription& body = scene.bodies[index];
  const std::string where = scene.file.string() + ": bodies[" + std::to_string(index) + "]";
  engine::BodyModel model;
  model.name = body.name;
  const BodyMatter matter = body_matter(body, index, where, keep_geometry, out);
  model.mass = matter.mass;

  // Inertia about the rotation centre (parallel axes for a pivot) and its principal frame.
  const Eigen::Vector3d centre = body.pivot.value_or(Eigen::Vector3d::Zero());  // body frame
  const engine::MassProperties about_com{model.mass, Eigen::Vector3d::Zero(), matter.inertia_com};
  const engine::PrincipalFrame frame =
      rotation_principal_frame(about_com.inertia_about(centre), matter, body.pivot.has_value());
  if (auto problem = engine::principal_moments_problem(frame.moments)) {
    throw InputError(where + (body.pivot ? ".pivot: inertia about the pivot: " : ": ") + *problem);
  }
  const Eigen::Matrix3d body_to_principal = frame.axes.transpose();
  model.moments = frame.moments;
  model.principal_to_body = Eigen::Quaterniond(frame.axes).normalized();
  model.center_offset = body_to_principal * -centre;  // the centre of mass from the centre
  if (body.pivot) {
    model.pivoted = true;
    model.pivot = body.position + body.orientation * centre;
  }

  add_forces(scene, body, centre, body_to_principal, model);
  out.initial.push_back(initial_state(body, model));
  out.bodies.push_back(std::move(model));
}

}  // namespace

CompiledScene compile_scene(const SceneDescription& scene, bool keep_geometry) {
  CompiledScene out;
  out.geometry.resize(scene.bodies.size());
  out.reports.resize(scene.bodies.size());
  out.settings = simulation_settings(scene);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) compile_body(scene, i, keep_geometry, out);
  return out;
}

}  // namespace tumble::app
