#pragma once
// Renderer-neutral description of one frame: plain structs filled by the caller (the app turns
// simulation state into these) and drawn by tumble::render::Renderer. Nothing here knows about
// OpenGL or physics. Lengths are in world units; screen positions are in pixels with the origin
// at the top-left corner of the image.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tumble::render {

/// Linear RGBA colour, each channel in [0, 1]; alpha < 1 draws translucently.
struct Rgba {
  float r = 1.0f;
  float g = 1.0f;
  float b = 1.0f;
  float a = 1.0f;
};

/// A triangle mesh in its own (body) frame, uploaded once with Renderer::upload.
struct MeshData {
  std::vector<Eigen::Vector3f> positions;  ///< vertex positions
  std::vector<std::uint32_t> indices;      ///< three per triangle, counter-clockwise outside
  /// Optional per-vertex normals (same size as positions). Empty: flat shading from the
  /// triangles' own normals.
  std::vector<Eigen::Vector3f> normals;
  /// The triangles bound solids and face out of them: every edge is run as often in one
  /// direction as in the other, and every connected part encloses a positive volume. Then an
  /// opaque copy seen from outside its bounding sphere is drawn without its back faces, which
  /// its front faces hide (on llvmpipe, back faces cost a third of a body's drawing). False
  /// (the default) draws both sides of every triangle, for open or inconsistently wound meshes.
  bool closed = false;
};

/// Handle of an uploaded mesh; valid for the Renderer that returned it.
struct MeshId {
  std::uint32_t value = 0;
  friend bool operator==(MeshId, MeshId) = default;
};

/// One drawn copy of an uploaded mesh.
struct MeshInstance {
  MeshId mesh;
  Eigen::Matrix4f pose = Eigen::Matrix4f::Identity();  ///< body-to-world transform
  Rgba colour{0.80f, 0.55f, 0.25f, 1.0f};              ///< alpha < 1: translucent
};

/// A 3D arrow: cylinder shaft and cone head, shaded like meshes.
struct Arrow {
  Eigen::Vector3f from = Eigen::Vector3f::Zero();
  Eigen::Vector3f to = Eigen::Vector3f::UnitX();
  Rgba colour{0.9f, 0.2f, 0.2f, 1.0f};
  float thickness = 0.02f;  ///< shaft diameter (world units); the head scales with it
};

/// A connected curve (trails, polhode, herpolhode) drawn with a constant screen width.
struct Polyline {
  std::vector<Eigen::Vector3f> points;
  Rgba colour{0.2f, 0.4f, 0.9f, 1.0f};
  float width_px = 2.0f;  ///< line width in pixels
};

/// A set of round dots with a constant screen size.
struct Points {
  std::vector<Eigen::Vector3f> positions;
  Rgba colour{0.1f, 0.1f, 0.1f, 1.0f};
  float size_px = 6.0f;  ///< dot diameter in pixels
};

/// Text drawn over the image, either attached to a 3D point or at a fixed screen position.
struct Label {
  std::string text;
  std::optional<Eigen::Vector3f> anchor;  ///< 3D anchor; when empty, `screen_px` is used
  Eigen::Vector2f screen_px = Eigen::Vector2f::Zero();  ///< top-left of the text, pixels
  Rgba colour{1.0f, 1.0f, 1.0f, 1.0f};
  /// Text height in pixels; 0: the frame's default, render::overlay_font_px(width, height).
  float font_px = 0.0f;
};

/// How a plot's vertical axis maps values.
enum class PlotAxis {
  kLinear,  ///< the values themselves
  kLog,     ///< log10 of |value|, floored at Plot::log_floor (quantities spanning decades)
};

/// A small time-series plot in an overlay panel: the curve between tick-labelled axes, with its
/// name and current value printed above it (outside the curve).
struct Plot {
  std::string name;
  std::vector<float> values;
  /// Fixed bounds of the vertical axis (default: the data's range); on a log axis they bound
  /// |value|. Several plots given the same bounds share one scale.
  std::optional<float> min;
  std::optional<float> max;
  float height_px = 60.0f;  ///< height of the curve's area (the caption line is extra)
  PlotAxis axis = PlotAxis::kLinear;
  float log_floor = 1e-16f;  ///< smallest |value| shown on a log axis
};

/// A translucent panel with a title, lines of text and plots (HUD of a video).
struct OverlayPanel {
  std::string title;
  Eigen::Vector2f position_px{10.0f, 10.0f};  ///< top-left corner of the panel
  float width_px = 280.0f;
  std::vector<std::string> lines;
  std::vector<Plot> plots;
  /// Text height in pixels; paddings and spacings scale with it (13: ImGui's default size).
  float font_px = 13.0f;
  /// A compact panel: no title bar (the title is not drawn), its lines packed with the tight
  /// padding and spacing of render::compact_panel_padding() and compact_panel_spacing(); a
  /// corner label for small frames such as the tiles of a comparison.
  bool compact = false;
};

/// A perspective pinhole camera.
struct Camera {
  Eigen::Vector3f eye{4.0f, -6.0f, 3.0f};
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  Eigen::Vector3f up = Eigen::Vector3f::UnitZ();
  float vertical_fov_deg = 40.0f;
  float near_plane = 0.05f;
  float far_plane = 200.0f;
};

/// Background, lights, ground and shadows.
struct SceneStyle {
  Rgba background_top{0.30f, 0.36f, 0.45f, 1.0f};     ///< colour of the image's top row
  Rgba background_bottom{0.82f, 0.84f, 0.87f, 1.0f};  ///< colour of the image's bottom row
  /// Direction the key light shines *from* (world, need not be normalised); casts the shadow.
  Eigen::Vector3f key_light_from{0.4f, -0.5f, 1.0f};
  bool ground = false;                                       ///< draw a ground plane
  Eigen::Vector3f ground_normal = Eigen::Vector3f::UnitZ();  ///< world "up" of the ground
  float ground_height = 0.0f;  ///< ground plane offset along ground_normal
  Rgba ground_colour{0.70f, 0.70f, 0.68f, 1.0f};
  bool shadows = true;  ///< soft shadow of the meshes on the ground (only when ground is on)
};

/// Everything drawn in one frame.
struct DrawList {
  Camera camera;
  SceneStyle style;
  std::vector<MeshInstance> meshes;
  std::vector<Arrow> arrows;
  std::vector<Polyline> polylines;
  std::vector<Points> points;
  std::vector<Label> labels;
  std::vector<OverlayPanel> panels;

  /// True when the frame needs the ImGui pass (text or panels).
  bool has_overlays() const { return !labels.empty() || !panels.empty(); }
};

}  // namespace tumble::render
