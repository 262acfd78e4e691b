// The viewer after its window is resized, without a window: Viewer::resize gives frames of the
// new size whose overlay text follows render::overlay_font_px at the session's font scale (the
// scene's render.font_scale unless --font-scale overrides it), a recording in progress is
// finished at its own size, and the control panel's rectangle follows the window and the text.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/viewer/viewer.hpp"
#include "app/viewer/viewer_panels.hpp"
#include "media/png_io.hpp"
#include "render/overlay_layout.hpp"
#include "render/renderer.hpp"
#include "support/command_test.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app::viewer {
namespace {

using ::testing::HasSubstr;

class ViewerResize : public testing::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    renderer_ = std::make_unique<render::Renderer>(render::RendererOptions{320, 240, 1});
    viewer_ = std::make_unique<Viewer>(*renderer_, dir_);
  }
  void TearDown() override {
    viewer_.reset();
    renderer_.reset();
    CommandTest::TearDown();
  }

  /// Opens a spinning brick whose scene asks for `font_scale` (none: the scene has no render).
  void open_brick(double font_scale = 0.0) {
    testing::SceneBuilder scene;
    scene.duration(5.0).dt(0.01).body(
        testing::BodyBuilder("brick").angular_velocity({0.1, 2.0, 0.1}));
    if (font_scale > 0.0) scene.render({{"font_scale", font_scale}});
    ASSERT_TRUE(viewer_->open(write_scene(scene.json())));
  }

  /// The text height of the scene overlay's panel in the next frame.
  float overlay_font_px() {
    const render::DrawList list = viewer_->frame();
    const auto panel = std::find_if(list.panels.begin(), list.panels.end(),
                                    [](const auto& p) { return p.title != "runs"; });
    return panel == list.panels.end() ? 0.0f : panel->font_px;
  }

  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<Viewer> viewer_;
};

TEST_F(ViewerResize, FramesTakeTheNewSizeAndTheOverlayItsText) {
  open_brick();
  viewer_->update(0.2);
  const double time = viewer_->session().time();
  for (const auto& [width, height] :
       std::vector<std::pair<int, int>>{{1280, 720}, {480, 270}, {1920, 1080}, {700, 900}}) {
    ASSERT_TRUE(viewer_->resize(width, height));
    const tumble::Image image = renderer_->render(viewer_->frame());
    EXPECT_EQ(image.width, width);
    EXPECT_EQ(image.height, height);
    EXPECT_EQ(overlay_font_px(), render::overlay_font_px(width, height)) << width << "x" << height;
  }
  // 13 px at 1280x720, 20 at 1920x1080, the 10 px floor at 480x270 (the oracle's own values).
  ASSERT_TRUE(viewer_->resize(1920, 1080));
  EXPECT_EQ(overlay_font_px(), 20.0f);
  ASSERT_TRUE(viewer_->resize(480, 270));
  EXPECT_EQ(overlay_font_px(), 10.0f);
  // Nothing restarted.
  EXPECT_EQ(viewer_->session().time(), time);
}

TEST_F(ViewerResize, TheScenesFontScaleAppliesAndTheOptionWins) {
  open_brick(2.0);
  EXPECT_EQ(viewer_->session().font_scale(), 2.0);
  ASSERT_TRUE(viewer_->resize(1280, 720));
  EXPECT_EQ(overlay_font_px(), 26.0f);  // 13 px x 2
  viewer_->session().set_font_scale(1.5);
  EXPECT_EQ(viewer_->session().font_scale(), 1.5);
  EXPECT_EQ(overlay_font_px(), 20.0f);  // round(19.5)
  ASSERT_TRUE(viewer_->resize(960, 720));
  EXPECT_EQ(overlay_font_px(), render::overlay_font_px(960, 720, 1.5));
  EXPECT_EQ(overlay_font_px(), 15.0f);  // round(13 x 0.75 x 1.5 = 14.6)
  // The option stays over a scene opened later; without it the scene's scale is back.
  open_brick(3.0);
  EXPECT_EQ(viewer_->session().font_scale(), 1.5);
  viewer_->session().set_font_scale(std::nullopt);
  EXPECT_EQ(viewer_->session().font_scale(), 3.0);
  EXPECT_EQ(overlay_font_px(), render::overlay_font_px(960, 720, 3.0));
}

TEST_F(ViewerResize, TheRunsLegendFollowsTheFrame) {
  open_brick();
  ASSERT_FALSE(viewer_->session().set_integrator("explicit-euler", 0.01, true).has_value());
  for (const auto& [width, height] : std::vector<std::pair<int, int>>{{1280, 720}, {480, 270}}) {
    ASSERT_TRUE(viewer_->resize(width, height));
    const render::DrawList list = viewer_->frame();
    const auto legend = std::find_if(list.panels.begin(), list.panels.end(),
                                     [](const auto& p) { return p.title == "runs"; });
    ASSERT_NE(legend, list.panels.end());
    EXPECT_EQ(legend->font_px, render::overlay_font_px(width, height));
    EXPECT_LE(legend->position_px.x() + legend->width_px, 0.5f * static_cast<float>(width) + 12.0f);
    EXPECT_LT(legend->position_px.y(), static_cast<float>(height));
  }
}

TEST_F(ViewerResize, ARecordingInProgressIsFinishedAtItsSize) {
  open_brick();
  viewer_->start_recording(dir_ / "frames/");
  ASSERT_TRUE(viewer_->recording());
  for (int i = 0; i < 3; ++i) {
    viewer_->update(1.0 / kRecordFps);
    tumble::Image scene = renderer_->render(viewer_->frame());
    viewer_->frame_drawn(&scene, scene);
  }
  ASSERT_TRUE(viewer_->resize(480, 270));
  EXPECT_FALSE(viewer_->recording());
  bool said = false;
  for (const Notice& notice : viewer_->notices()) {
    EXPECT_FALSE(notice.error) << notice.text;
    said |= notice.text.find("recording stopped: the window was resized") != std::string::npos;
  }
  EXPECT_TRUE(said);
  const std::vector<std::string> frames = testing::directory_entries(dir_ / "frames");
  ASSERT_GE(frames.size(), 3u);
  for (const std::string& name : frames) {
    const tumble::Image frame = media::read_png(dir_ / "frames" / name);
    EXPECT_EQ(frame.width, 320) << name;
    EXPECT_EQ(frame.height, 240) << name;
  }
}

TEST(ViewerPanelRect, FollowsTheWindowAndTheText) {
  // 13 px text in a 1280x720 window: 360 px wide, 10 px margins.
  const PanelRect wide = panel_rect(1280, 720, 13.0f);
  EXPECT_EQ(wide.width, 360.0f);
  EXPECT_EQ(wide.x, 1280.0f - 360.0f - 10.0f);
  EXPECT_EQ(wide.y, 10.0f);
  EXPECT_EQ(wide.height, 700.0f);
  // 20 px text at 1920x1080: everything 20/13 as large (whole pixels).
  const PanelRect large = panel_rect(1920, 1080, 20.0f);
  EXPECT_EQ(large.width, 553.0f);  // floor(360 x 20 / 13 = 553.8)
  EXPECT_EQ(large.y, 15.0f);       // round(15.4)
  EXPECT_EQ(large.x + large.width + large.y, 1920.0f);
  // A small window: 45 % of its width at most, the view keeps the rest.
  for (const auto& [width, height] : std::vector<std::pair<int, int>>{{480, 270}, {320, 180}}) {
    const float px = render::overlay_font_px(width, height);
    const PanelRect small = panel_rect(width, height, px);
    EXPECT_LE(small.width, 0.45f * static_cast<float>(width));
    EXPECT_GE(small.width, 0.45f * static_cast<float>(width) - 1.0f);
    EXPECT_GE(small.x, 0.5f * static_cast<float>(width));
    EXPECT_EQ(small.height, static_cast<float>(height) - 2.0f * small.y);
  }
  // Never a negative height.
  EXPECT_GT(panel_rect(50, 5, 13.0f).height, 0.0f);
}

}  // namespace
}  // namespace tumble::app::viewer
