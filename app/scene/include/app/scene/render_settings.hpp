#pragma once
/// @file What a rendered frame shows and how: the scene's optional `render` object.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

namespace tumble::app {

/// Where the camera is.
struct CameraSettings {
  enum class Mode { kFixed, kOrbit, kFollow };
  Mode mode = Mode::kFixed;
  /// Explicit eye and target (world, m). Without them the camera frames the whole motion
  /// automatically (see FrameBuilder), from `azimuth_deg` and `elevation_deg`.
  std::optional<Eigen::Vector3d> eye;
  std::optional<Eigen::Vector3d> target;
  double fov_deg = 40.0;           ///< vertical field of view
  std::optional<double> distance;  ///< m from the target (default: auto-framing)
  double azimuth_deg = -60.0;      ///< about world z, from +x
  double elevation_deg = 25.0;     ///< above the xy plane
  double orbit_period = 30.0;      ///< s of simulation time per turn (orbit mode)
  std::size_t follow_body = 0;     ///< body index the camera follows (follow mode)
};

/// A trail: the world path of a point fixed in a body.
struct TrailSettings {
  std::size_t body = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< body frame (m, from the centre of mass)
  double seconds = 5.0;                             ///< how much history is drawn
};

/// What a frame shows; each item switchable in the scene's `render.show` object.
struct ShowSettings {
  bool bodies = true;
  bool body_axes = false;          ///< the user's body frame (mesh axes at the centre of mass)
  bool principal_axes = false;     ///< principal axes, scaled by the moments
  bool angular_velocity = true;    ///< world w arrow at the centre
  bool angular_momentum = true;    ///< world L arrow (fixed for a free body)
  bool herpolhode = false;         ///< path of the tip of w in the world
  bool polhode = false;            ///< path of the tip of w in the body frame (drawn on the body)
  bool inertia_ellipsoid = false;  ///< Poinsot's ellipsoid, translucent, moving with the body
  bool ground = false;             ///< a ground plane with soft shadows
  bool overlay = true;             ///< title, integrator, dt, time, energy and |L| drift plots
  std::vector<TrailSettings> trails;
};

/// Limits of the render settings, the same from a scene's `render` object and from the
/// command line's --size, --fps and --aa.
inline constexpr int kMaxImageSide = 8192;   ///< pixels
inline constexpr double kMaxFps = 240.0;     ///< frames per second
inline constexpr int kMaxAntialiasing = 16;  ///< samples per pixel
/// Limits of the overlay's text scale (render.font_scale, --font-scale).
inline constexpr double kMinFontScale = 0.25;
inline constexpr double kMaxFontScale = 8.0;

/// How video frames are anti-aliased: `render.antialiasing` and --aa take "off", "fxaa" (the
/// default: a post-process filter at ~1.15x the time of an aliased frame) or a number of
/// multisampling samples per pixel, 2 to kMaxAntialiasing (1 means off, as in older scenes).
struct Antialiasing {
  enum class Mode { kOff, kFxaa, kMultisample };
  Mode mode = Mode::kFxaa;
  int samples = 1;  ///< multisampling samples per pixel (1 unless kMultisample)
  bool operator==(const Antialiasing&) const = default;
};

/// "off", "fxaa" or a whole number of samples from 1 (off) to kMaxAntialiasing; nothing for any
/// other text.
std::optional<Antialiasing> antialiasing_from_text(const std::string& text);
/// A sample count from 1 (off) to kMaxAntialiasing (the caller checks the range).
Antialiasing antialiasing_samples(int samples);
/// What a bad value gets told: the accepted values.
inline constexpr const char* kAntialiasingExpected =
    "expected off, fxaa or multisampling samples per pixel from 2 to 16 (1: off)";

/// Everything `tumble render` needs beyond the simulation.
struct RenderSettings {
  int width = 1280;
  int height = 720;
  double fps = 30.0;
  double time_scale = 1.0;    ///< simulated seconds per second of video
  Antialiasing antialiasing;  ///< FXAA unless the scene or --aa says otherwise
  /// Draw big meshes from simplified copies under a pixel off (render::RendererOptions::lod);
  /// false: always the full mesh.
  bool lod = true;
  CameraSettings camera;
  ShowSettings show;
  /// Text size of the overlay relative to the frame's own (1: 13 px at 1280x720, proportional
  /// to the frame; the text is never drawn under 10 px).
  double font_scale = 1.0;
};

/// Reads a scene's `render` object (all keys optional; unknown keys, wrong types and
/// impossible values throw tumble::InputError naming `source` and the JSON path, e.g.
/// `render.camera.mode`). `body_names` resolves body references by name.
RenderSettings parse_render_settings(const nlohmann::json& render, const std::string& source,
                                     const std::vector<std::string>& body_names);

}  // namespace tumble::app
