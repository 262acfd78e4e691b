// The scene's `render` object: what a video shows and how (JSON -> RenderSettings).
//
// As in scene files, every error names the source, the JSON path from `render` down and what
// was expected (app/json_field.hpp).
#include "app/scene/render_settings.hpp"

#include <charconv>
#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string_view>

#include "app/scene/json_field.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using tumble::InputError;

using Field = JsonField;

/// The index of the body named by `field` (a string).
std::size_t body_index(const Field& field, const std::vector<std::string>& body_names) {
  const std::string name = field.string();
  for (std::size_t i = 0; i < body_names.size(); ++i) {
    if (body_names[i] == name) return i;
  }
  std::string names;
  for (const std::string& known : body_names) names += (names.empty() ? "" : ", ") + known;
  field.fail("no body is named \"" + name + "\"; the bodies are: " + names);
}

CameraSettings parse_camera(const Field& field, const std::vector<std::string>& body_names) {
  field.expect_object({"mode", "eye", "target", "fov", "distance", "azimuth", "elevation",
                       "orbit_period", "follow"});
  CameraSettings camera;
  if (auto mode = field.find("mode")) {
    const std::string text = mode->string();
    if (text == "fixed") {
      camera.mode = CameraSettings::Mode::kFixed;
    } else if (text == "orbit") {
      camera.mode = CameraSettings::Mode::kOrbit;
    } else if (text == "follow") {
      camera.mode = CameraSettings::Mode::kFollow;
    } else {
      mode->fail("expected one of fixed, orbit, follow, got \"" + text + "\"");
    }
  }
  if (auto eye = field.find("eye")) camera.eye = eye->vector3();
  if (auto target = field.find("target")) camera.target = target->vector3();
  if (camera.eye && camera.target && (*camera.eye - *camera.target).norm() <= 0.0) {
    field.find("eye")->fail("the eye must differ from the target");
  }
  if (auto fov = field.find("fov")) camera.fov_deg = fov->in_range(1.0, 170.0);
  if (auto distance = field.find("distance")) camera.distance = distance->positive();
  if (auto azimuth = field.find("azimuth")) camera.azimuth_deg = azimuth->number();
  // Straight up or down leaves the look-at camera without a horizon.
  if (auto elevation = field.find("elevation")) camera.elevation_deg = elevation->in_range(-89, 89);
  if (auto period = field.find("orbit_period")) camera.orbit_period = period->positive();
  if (auto follow = field.find("follow")) camera.follow_body = body_index(*follow, body_names);
  return camera;
}

TrailSettings parse_trail(const Field& field, const std::vector<std::string>& body_names) {
  field.expect_object({"body", "point", "seconds"});
  TrailSettings trail;
  if (auto body = field.find("body")) {
    trail.body = body_index(*body, body_names);
  } else if (body_names.size() > 1) {
    field.fail("missing \"body\": name the body the trail follows (the scene has " +
               std::to_string(body_names.size()) + ")");
  }
  if (auto point = field.find("point")) trail.point = point->vector3();
  if (auto seconds = field.find("seconds")) trail.seconds = seconds->positive();
  return trail;
}

ShowSettings parse_show(const Field& field, const std::vector<std::string>& body_names) {
  field.expect_object({"bodies", "body_axes", "principal_axes", "angular_velocity",
                       "angular_momentum", "herpolhode", "polhode", "inertia_ellipsoid", "ground",
                       "overlay", "trails"});
  ShowSettings show;
  const std::pair<std::string_view, bool*> switches[] = {
      {"bodies", &show.bodies},
      {"body_axes", &show.body_axes},
      {"principal_axes", &show.principal_axes},
      {"angular_velocity", &show.angular_velocity},
      {"angular_momentum", &show.angular_momentum},
      {"herpolhode", &show.herpolhode},
      {"polhode", &show.polhode},
      {"inertia_ellipsoid", &show.inertia_ellipsoid},
      {"ground", &show.ground},
      {"overlay", &show.overlay},
  };
  for (const auto& [key, target] : switches) {
    if (auto value = field.find(key)) *target = value->boolean();
  }
  if (auto trails = field.find("trails")) {
    if (!trails->value().is_array()) {
      trails->fail("expected an array of trails [{\"body\", \"point\", \"seconds\"}], got " +
                   describe(trails->value()));
    }
    for (std::size_t i = 0; i < trails->value().size(); ++i) {
      show.trails.push_back(parse_trail(trails->element(i), body_names));
    }
  }
  return show;
}

/// `render.antialiasing`: "off", "fxaa" or samples per pixel (1: off).
Antialiasing parse_antialiasing(const Field& field) {
  if (field.value().is_string()) {
    const std::string text = field.string();
    if (text == "off" || text == "fxaa") return *antialiasing_from_text(text);
  } else if (field.value().is_number_integer() || field.value().is_number_unsigned()) {
    const long long samples = field.value().get<long long>();
    if (samples >= 1 && samples <= kMaxAntialiasing) {
      return antialiasing_samples(static_cast<int>(samples));
    }
  }
  field.fail(std::string(kAntialiasingExpected) + ", got " + field.value().dump());
}

}  // namespace

Antialiasing antialiasing_samples(int samples) {
  return samples <= 1 ? Antialiasing{Antialiasing::Mode::kOff, 1}
                      : Antialiasing{Antialiasing::Mode::kMultisample, samples};
}

std::optional<Antialiasing> antialiasing_from_text(const std::string& text) {
  if (text == "off") return Antialiasing{Antialiasing::Mode::kOff, 1};
  if (text == "fxaa") return Antialiasing{};
  int samples = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, samples);
  if (text.empty() || error != std::errc() || stop != end || samples < 1 ||
      samples > kMaxAntialiasing) {
    return std::nullopt;
  }
  return antialiasing_samples(samples);
}

RenderSettings parse_render_settings(const nlohmann::json& render, const std::string& source,
                                     const std::vector<std::string>& body_names) {
  const Field top(render, "render", source);
  top.expect_object(
      {"size", "fps", "time_scale", "antialiasing", "camera", "show", "font_scale", "lod"});
  RenderSettings settings;

  // Image size: even sides (yuv420p halves both for the chroma planes).
  if (auto size = top.find("size")) {
    size->expect_array(2, "an image size [width, height] in pixels");
    const int sides[2] = {size->element(0).integer(2, kMaxImageSide),
                          size->element(1).integer(2, kMaxImageSide)};
    for (std::size_t i = 0; i < 2; ++i) {
      if (sides[i] % 2 != 0) {
        size->element(i).fail("expected an even number of pixels (video encoders need it), got " +
                              std::to_string(sides[i]));
      }
    }
    settings.width = sides[0];
    settings.height = sides[1];
  }

  // Timing and quality.
  if (auto fps = top.find("fps")) {
    settings.fps = fps->positive();
    if (settings.fps > kMaxFps) {
      fps->fail("expected at most " + number_text(kMaxFps) + " frames per second, got " +
                number_text(settings.fps));
    }
  }
  if (auto scale = top.find("time_scale")) settings.time_scale = scale->positive();
  if (auto antialiasing = top.find("antialiasing"))
    settings.antialiasing = parse_antialiasing(*antialiasing);

  if (auto scale = top.find("font_scale")) {
    settings.font_scale = scale->positive();
    if (settings.font_scale < kMinFontScale || settings.font_scale > kMaxFontScale) {
      scale->fail("expected a text scale from " + number_text(kMinFontScale) + " to " +
                  number_text(kMaxFontScale) + ", got " + number_text(settings.font_scale));
    }
  }
  if (auto lod = top.find("lod")) settings.lod = lod->boolean();

  // What is seen, and from where.
  if (auto camera = top.find("camera")) settings.camera = parse_camera(*camera, body_names);
  if (auto show = top.find("show")) settings.show = parse_show(*show, body_names);
  return settings;
}

}  // namespace tumble::app
