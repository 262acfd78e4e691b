// Scene files: parsing and validation (JSON -> SceneDescription); the compilation to engine
// bodies, states and settings is in scene_compile.cpp.
#include "app/scene/scene.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "app/scene/json_field.hpp"
#include "app/scene/shape_field.hpp"
#include "app/scene/strict_json.hpp"
#include "app/support/text_file.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/import/mesh_import.hpp"
#include "engine/mass/principal_frame.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using tumble::InputError;

using Field = JsonField;

VectorFrame parse_frame(const Field& field) {
  const std::string text = field.string();
  if (text == "world") return VectorFrame::kWorld;
  if (text == "body") return VectorFrame::kBody;
  field.fail("expected \"world\" or \"body\", got \"" + text + "\"");
}

/// "[a, b, c]" for messages.
std::string vector_text(const Eigen::Vector3d& v) {
  std::string text("[");
  for (int i = 0; i < 3; ++i) text.append(i ? ", " : "").append(number_text(v[i]));
  return text.append("]");
}

Eigen::Quaterniond parse_quaternion(const Field& field) {
  field.expect_array(4, "a quaternion [w, x, y, z] of 4 finite numbers");
  const Eigen::Quaterniond q(field.element(0).number(), field.element(1).number(),
                             field.element(2).number(), field.element(3).number());
  // Any non-zero quaternion is accepted and normalised (hand-written rotations like
  // [1, 0, 0, 1] are common); one too small to normalise is refused.
  const double norm = q.norm();
  if (!(norm >= std::numeric_limits<double>::min())) {
    field.fail("expected a non-zero quaternion [w, x, y, z], got [0, 0, 0, 0]");
  }
  return Eigen::Quaterniond(q.coeffs() / norm);
}

Eigen::Matrix3d parse_tensor(const Field& field) {
  field.expect_array(3, "a 3 x 3 array [[Ixx, Ixy, Ixz], [Iyx, Iyy, Iyz], [Izx, Izy, Izz]]");
  Eigen::Matrix3d tensor;
  for (std::size_t r = 0; r < 3; ++r) {
    const Field row = field.element(r);
    row.expect_array(3, "a row of 3 finite numbers");
    for (std::size_t c = 0; c < 3; ++c) {
      tensor(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = row.element(c).number();
    }
  }
  // Symmetric up to rounding in the printed digits; then keep the exact symmetric part.
  const double tolerance = 1e-9 * tensor.cwiseAbs().maxCoeff();
  for (int r = 0; r < 3; ++r) {
    for (int c = r + 1; c < 3; ++c) {
      if (std::abs(tensor(r, c) - tensor(c, r)) > tolerance) {
        field.fail("expected a symmetric tensor, but [" + std::to_string(r) + "][" +
                   std::to_string(c) + "] = " + number_text(tensor(r, c)) + " differs from [" +
                   std::to_string(c) + "][" + std::to_string(r) +
                   "] = " + number_text(tensor(c, r)));
      }
    }
  }
  tensor = 0.5 * (tensor + tensor.transpose()).eval();
  const engine::PrincipalFrame frame = engine::principal_frame(tensor);
  if (frame.moments.minCoeff() <= 0.0) {
    field.fail("expected a positive definite tensor; its principal moments are " +
               vector_text(frame.moments));
  }
  if (auto problem = engine::principal_moments_problem(frame.moments)) field.fail(*problem);
  return tensor;
}

void parse_inertia(const Field& field, BodyDescription& body) {
  field.expect_object({"principal", "tensor"});
  const auto principal = field.find("principal");
  const auto tensor = field.find("tensor");
  if (principal.has_value() == tensor.has_value()) {
    field.fail("expected exactly one of \"principal\" ([I1, I2, I3]) or \"tensor\" (3 x 3)");
  }
  if (principal) {
    const Eigen::Vector3d moments = principal->vector3();
    if (auto problem = engine::principal_moments_problem(moments)) principal->fail(*problem);
    body.principal_moments = moments;
  } else {
    body.inertia_tensor = parse_tensor(*tensor);
  }
}

SpringDescription parse_spring(const Field& field) {
  field.expect_object({"anchor", "attach", "stiffness", "damping"});
  SpringDescription spring;
  spring.anchor =
      field.require("anchor", "the world point [x, y, z] the spring is tied to").vector3();
  spring.attach =
      field.require("attach", "the body point [x, y, z] (body frame, from the centre of mass)")
          .vector3();
  spring.stiffness = field.require("stiffness", "a stiffness in N/m (>= 0)").non_negative();
  if (auto damping = field.find("damping")) spring.damping = damping->non_negative();
  return spring;
}

/// Name: non-empty and printable (it keys the CSV rows); unique, as the caller checks.
void parse_body_name(const Field& field, std::size_t index, BodyDescription& body) {
  body.name = "body" + std::to_string(index);
  if (auto name = field.find("name")) {
    body.name = name->string();
    if (body.name.empty()) name->fail("expected a non-empty name");
    for (char c : body.name) {
      if (static_cast<unsigned char>(c) < 0x20)
        name->fail("expected a name without control characters");
    }
  }
}

/// Shape: a mesh (relative to the scene's folder), a primitive shape or an inertia: one only.
void parse_body_shape(const Field& field, const std::filesystem::path& folder,
                      BodyDescription& body) {
  const auto mesh = field.find("mesh");
  const auto shape = field.find("shape");
  const auto inertia = field.find("inertia");
  const int given = int(mesh.has_value()) + int(shape.has_value()) + int(inertia.has_value());
  if (given != 1) {
    field.fail(given ? "expected exactly one of \"mesh\", \"shape\" or \"inertia\", got " +
                           std::to_string(given) + " of them"
                     : "expected exactly one of \"mesh\" (a file), \"shape\" ({\"box\": [x, y, "
                       "z]}, {\"sphere\": {\"radius\": r}}, ...) or \"inertia\" ({\"principal\": "
                       "[..]} or {\"tensor\": [[..], [..], [..]]}), got none");
  }
  if (mesh) {
    const std::string text = mesh->string();
    if (text.empty()) mesh->fail("expected a mesh file path, got an empty string");
    const std::filesystem::path path(text);
    body.mesh = path.is_absolute() ? path : folder / path;
  } else if (shape) {
    body.shape = parse_shape(*shape);
  } else {
    parse_inertia(*inertia, body);
  }
}

/// Matter: mass or density with a mesh or shape, mass with an inertia; scale with a mesh only.
void parse_body_matter(const Field& field, BodyDescription& body) {
  const bool mesh = body.mesh.has_value();
  const bool solid = mesh || body.shape.has_value();
  const auto mass = field.find("mass");
  const auto density = field.find("density");
  if (mass && density) density->fail("\"mass\" and \"density\" exclude each other: give one");
  if (mass) body.mass = mass->positive();
  if (density) {
    if (!solid) {
      density->fail("\"density\" needs a mesh or a shape; with \"inertia\" give \"mass\"");
    }
    body.density = density->positive();
  }
  if (!mass && !density) {
    field.fail(solid ? std::string("missing \"mass\" (kg) or \"density\" (kg/m^3) for the ") +
                           (mesh ? "mesh" : "shape")
                     : "missing \"mass\" (kg): the inertia alone does not fix it");
  }
  if (auto scale = field.find("scale")) {
    if (!mesh) scale->fail("\"scale\" applies to a mesh only (mesh units to metres)");
    body.scale = scale->positive();
  }
  if (auto allow = field.find("allow_overlap")) {
    if (!mesh) allow->fail("\"allow_overlap\" applies to a mesh only");
    if (field.find("overlap")) allow->fail("give \"overlap\" or \"allow_overlap\", not both");
    body.overlap = allow->boolean() ? engine::OverlapMode::kSum : engine::OverlapMode::kRefuse;
  }
  if (auto overlap = field.find("overlap")) {
    if (!mesh) overlap->fail("\"overlap\" applies to a mesh only");
    const std::string name = overlap->string();
    const auto mode = engine::overlap_mode_named(name);
    if (!mode) overlap->fail("expected \"union\", \"sum\" or \"refuse\", got \"" + name + "\"");
    body.overlap = *mode;
  }
  if (auto method = field.find("inertia_method")) {
    if (!mesh) method->fail("\"inertia_method\" applies to a mesh only");
    const std::string name = method->string();
    const auto parsed = engine::parse_inertia_method(name);
    if (!parsed)
      method->fail("expected \"exact\", \"convex\", \"shell\", \"legacy\" or \"auto\", got \"" +
                   name + "\"");
    body.inertia_method = *parsed;
  }
}

void parse_initial_state(const Field& field, BodyDescription& body) {
  if (auto position = field.find("position")) body.position = position->vector3();
  if (auto orientation = field.find("orientation"))
    body.orientation = parse_quaternion(*orientation);
  if (auto omega = field.find("angular_velocity")) body.angular_velocity = omega->vector3();
  if (auto frame = field.find("angular_velocity_frame")) {
    if (!field.find("angular_velocity")) frame->fail("given without \"angular_velocity\"");
    body.angular_velocity_frame = parse_frame(*frame);
  }
  if (auto pivot = field.find("pivot")) body.pivot = pivot->vector3();
  if (auto velocity = field.find("velocity")) {
    if (body.pivot) {
      velocity->fail(
          "a pivoted body takes no \"velocity\": it follows from the rotation about "
          "the pivot");
    }
    body.velocity = velocity->vector3();
  }
}

void parse_loads(const Field& field, BodyDescription& body) {
  if (auto torque = field.find("torque")) body.torque = torque->vector3();
  if (auto frame = field.find("torque_frame")) {
    if (!body.torque) frame->fail("given without \"torque\"");
    body.torque_frame = parse_frame(*frame);
  }
  if (auto spring = field.find("spring")) body.spring = parse_spring(*spring);
}

BodyDescription parse_body(const Field& field, std::size_t index,
                           const std::filesystem::path& folder) {
  field.expect_object({"name", "mesh", "shape", "inertia", "mass", "density", "scale",
                       "allow_overlap", "overlap", "inertia_method", "position", "orientation",
                       "velocity", "angular_velocity", "angular_velocity_frame", "pivot", "torque",
                       "torque_frame", "spring"});
  BodyDescription body;
  parse_body_name(field, index, body);
  parse_body_shape(field, folder, body);
  parse_body_matter(field, body);
  parse_initial_state(field, body);
  parse_loads(field, body);
  return body;
}

}  // namespace

SceneDescription parse_scene(const std::string& text, const std::filesystem::path& file) {
  const std::string source = file.string();

  // Read the JSON (comments allowed; syntax errors by line and column).
  const json root = parse_strict_json(text, source);
  const Field top(root, "", source);
  top.expect_object({"name", "duration", "dt", "integrator", "tolerance", "absolute_tolerance",
                     "gravity", "bodies", "render"});

  SceneDescription scene;
  scene.file = file;
  scene.name = file.stem().string();
  if (auto name = top.find("name")) scene.name = name->string();

  // Time and integrator.
  scene.duration =
      top.require("duration", "the simulated time in seconds (a positive number)").positive();
  const Field dt = top.require("dt", "the time step in seconds (a positive number)");
  scene.dt = dt.positive();
  if (auto problem = step_problem(scene.dt, scene.duration)) dt.fail(*problem);
  if (auto integrator = top.find("integrator")) {
    scene.integrator = integrator->string();
    if (!engine::integrator_from_name(scene.integrator)) {
      integrator->fail("unknown integrator \"" + scene.integrator +
                       "\"; expected one of: " + integrator_names());
    }
  }
  if (auto tolerance = top.find("tolerance")) scene.tolerance = tolerance->positive();
  if (auto absolute = top.find("absolute_tolerance")) {
    scene.absolute_tolerance = absolute->non_negative();
  }
  if (auto gravity = top.find("gravity")) scene.gravity = gravity->vector3();
  // The render object is read by the render command (parse_render_settings), not here.
  if (auto render = top.find("render")) scene.render = render->value();

  // Bodies, with unique names.
  const Field bodies = top.require("bodies", "a non-empty array of bodies");
  if (!bodies.value().is_array() || bodies.value().empty()) {
    bodies.fail("expected a non-empty array of bodies, got " + describe(bodies.value()));
  }
  const std::filesystem::path folder = file.parent_path();
  std::map<std::string, std::size_t> names;
  for (std::size_t i = 0; i < bodies.value().size(); ++i) {
    const Field field = bodies.element(i);
    scene.bodies.push_back(parse_body(field, i, folder));
    const auto [it, inserted] = names.emplace(scene.bodies.back().name, i);
    if (!inserted) {
      const auto name = field.find("name");
      (name ? *name : field)
          .fail("the name \"" + it->first + "\" is already taken by bodies[" +
                std::to_string(it->second) + "]; body names must be unique");
    }
  }
  return scene;
}

std::optional<std::string> step_problem(double dt, double duration) {
  if (dt > duration) {
    return "expected a step no longer than the duration (" + number_text(duration) + " s), got " +
           number_text(dt);
  }
  if (duration / dt > kMaxSteps) {
    char steps[32];
    std::snprintf(steps, sizeof steps, "%.3g", duration / dt);
    return "expected at most 1e12 steps, but a duration of " + number_text(duration) + " s takes " +
           steps + " steps of " + number_text(dt) + " s";
  }
  return std::nullopt;
}

SceneDescription load_scene(const std::filesystem::path& file) {
  return parse_scene(read_text_file(file, "scene file (JSON)"), file);
}

std::string integrator_names() {
  std::string names;
  for (const engine::IntegratorInfo& info : engine::integrator_catalog()) {
    names += (names.empty() ? "" : ", ") + info.name;
  }
  return names;
}

void override_integrator(SceneDescription& scene, const std::string& name) {
  if (!engine::integrator_from_name(name)) {
    throw InputError("--integrator: unknown integrator \"" + name +
                     "\"; expected one of: " + integrator_names());
  }
  scene.integrator = name;
}

double positive_option(double value, const char* option) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw InputError(std::string(option) + ": expected a positive finite number, got " +
                     number_text(value));
  }
  return value;
}

std::vector<std::filesystem::path> scene_inputs(const SceneDescription& scene) {
  std::vector<std::filesystem::path> inputs = {scene.file};
  for (const BodyDescription& body : scene.bodies) {
    if (body.mesh) inputs.push_back(*body.mesh);
  }
  return inputs;
}

}  // namespace tumble::app
