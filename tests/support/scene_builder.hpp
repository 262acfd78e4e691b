#pragma once
// Scene files for tests: a small builder producing the JSON of a scene (see docs/scenes.md), so
// every test states only what its scene is about.
//
//   SceneBuilder().duration(5).dt(0.003)
//       .body(BodyBuilder("brick").angular_velocity({0.1, 2.0, 0.1}))
//       .json()
//
// A body starts as a free brick named "brick": principal moments 1 : 2 : 3, mass 2 kg, at
// rest at the origin. A scene starts with duration 1 s, dt 0.01 s and no bodies; every other
// key is absent until set, so the scene's own defaults apply.

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace tumble::testing {

/// One element of a scene's "bodies".
class BodyBuilder {
 public:
  explicit BodyBuilder(const std::string& name = "brick") {
    json_ = {{"name", name}, {"inertia", {{"principal", {1.0, 2.0, 3.0}}}}, {"mass", 2.0}};
  }

  /// inertia: {"principal": [a, b, c]} (kg m^2).
  BodyBuilder& principal(const Eigen::Vector3d& moments) {
    return set("inertia", {{"principal", vector(moments)}});
  }
  BodyBuilder& mass(double kg) { return set("mass", kg); }
  BodyBuilder& position(const Eigen::Vector3d& x) { return set("position", vector(x)); }
  BodyBuilder& velocity(const Eigen::Vector3d& v) { return set("velocity", vector(v)); }
  /// angular_velocity, and angular_velocity_frame when `frame` is given ("body", "world").
  BodyBuilder& angular_velocity(const Eigen::Vector3d& w, const std::string& frame = "") {
    set("angular_velocity", vector(w));
    return frame.empty() ? *this : set("angular_velocity_frame", frame);
  }
  /// orientation as a quaternion [w, x, y, z].
  BodyBuilder& orientation(double w, double x, double y, double z) {
    return set("orientation", {w, x, y, z});
  }
  BodyBuilder& torque(const Eigen::Vector3d& t) { return set("torque", vector(t)); }
  /// Any other key (or a replacement for one above).
  BodyBuilder& set(const std::string& key, nlohmann::json value) {
    json_[key] = std::move(value);
    return *this;
  }
  BodyBuilder& erase(const std::string& key) {
    json_.erase(key);
    return *this;
  }

  const nlohmann::json& json() const { return json_; }

 private:
  static nlohmann::json vector(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
  nlohmann::json json_;
};

/// A whole scene file.
class SceneBuilder {
 public:
  SceneBuilder() { json_ = {{"duration", 1.0}, {"dt", 0.01}, {"bodies", nlohmann::json::array()}}; }

  SceneBuilder& name(const std::string& name) { return set("name", name); }
  SceneBuilder& duration(double seconds) { return set("duration", seconds); }
  SceneBuilder& dt(double seconds) { return set("dt", seconds); }
  SceneBuilder& integrator(const std::string& name) { return set("integrator", name); }
  /// The "render" object.
  SceneBuilder& render(nlohmann::json render) { return set("render", std::move(render)); }
  /// Appends a body.
  SceneBuilder& body(const BodyBuilder& body) {
    json_["bodies"].push_back(body.json());
    return *this;
  }
  /// Any other key (or a replacement for one above).
  SceneBuilder& set(const std::string& key, nlohmann::json value) {
    json_[key] = std::move(value);
    return *this;
  }

  const nlohmann::json& json() const { return json_; }
  /// The scene file's text (indented JSON).
  std::string text() const { return json_.dump(2); }
  /// Writes text() to `file` and returns `file`.
  std::filesystem::path write(const std::filesystem::path& file) const {
    std::ofstream out(file);
    out << text();
    if (!out) throw std::runtime_error("cannot write " + file.string());
    return file;
  }

 private:
  nlohmann::json json_;
};

/// A scene of one box-shaped body (given by its moments, no mesh) tumbling about its
/// intermediate axis, under rk4.
inline nlohmann::json tumbling_scene(double duration = 0.5, double dt = 0.01) {
  return SceneBuilder()
      .name("test tumble")
      .duration(duration)
      .dt(dt)
      .integrator("rk4")
      .body(BodyBuilder("brick").angular_velocity({0.3, 6.0, 0.3}, "body"))
      .json();
}

}  // namespace tumble::testing
