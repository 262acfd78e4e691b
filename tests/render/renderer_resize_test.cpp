// Renderer::resize (the viewer's window resized): a resized renderer draws what a renderer made
// at the new size draws, pixel for pixel, with the meshes uploaded before the resize, for each
// kind of anti-aliasing; a bad size is refused and the old one kept.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>
#include <utility>
#include <vector>

#include "render/renderer.hpp"
#include "render_support.hpp"

namespace tumble::render {
namespace {

/// A turned box over a gradient, with a label: the aspect, the ground and the overlay all
/// depend on the frame's size.
DrawList resized_box_frame(MeshId box) {
  DrawList frame;
  frame.camera.eye = {3.0f, -4.0f, 2.5f};
  frame.style.ground = true;
  frame.style.shadows = true;
  frame.style.ground_height = -0.4f;
  const Eigen::Affine3f pose(Eigen::AngleAxisf(0.5f, Eigen::Vector3f::UnitZ()));
  frame.meshes.push_back({box, pose.matrix(), {0.85f, 0.55f, 0.25f, 1.0f}});
  frame.labels.push_back({"w", Eigen::Vector3f(0.0f, 0.0f, 0.6f), {}, {1, 1, 0, 1}});
  return frame;
}

Image render_box(Renderer& renderer, MeshId box) {
  return renderer.render(resized_box_frame(box));
}

class RendererResize : public ::testing::TestWithParam<std::pair<int, AntialiasingFilter>> {};

TEST_P(RendererResize, DrawsWhatARendererOfTheNewSizeDraws) {
  const auto [samples, filter] = GetParam();
  RendererOptions options{320, 180, samples, true, filter};
  Renderer resized(options);
  const MeshId box = resized.upload(testing::box_mesh({0.6f, 0.4f, 0.3f}));
  render_box(resized, box);  // a frame at the first size, so every pass has run once
  // Wider, then taller than wide, then back: each frame as a fresh renderer of that size.
  for (const auto& [width, height] :
       std::vector<std::pair<int, int>>{{400, 150}, {135, 240}, {320, 180}}) {
    resized.resize(width, height);
    ASSERT_EQ(resized.width(), width);
    ASSERT_EQ(resized.height(), height);
    const Image image = render_box(resized, box);
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);
    options.width = width;
    options.height = height;
    Renderer fresh(options);
    const Image expected = render_box(fresh, fresh.upload(testing::box_mesh({0.6f, 0.4f, 0.3f})));
    EXPECT_EQ(resized.samples(), fresh.samples());
    EXPECT_EQ(resized.filter(), fresh.filter());
    EXPECT_TRUE(image.rgba == expected.rgba) << width << "x" << height;
  }
}

INSTANTIATE_TEST_SUITE_P(Antialiasing, RendererResize,
                         ::testing::Values(std::pair{1, AntialiasingFilter::none},
                                           std::pair{4, AntialiasingFilter::none},
                                           std::pair{1, AntialiasingFilter::fxaa}));

TEST(RendererResizeErrors, ABadSizeIsRefusedAndTheOldOneKept) {
  Renderer renderer({320, 240, 1});
  const MeshId box = renderer.upload(testing::box_mesh({0.6f, 0.4f, 0.3f}));
  const Image before = render_box(renderer, box);
  EXPECT_THROW(renderer.resize(0, 240), std::invalid_argument);
  EXPECT_THROW(renderer.resize(320, -1), std::invalid_argument);
  EXPECT_THROW(renderer.resize(16385, 240), std::invalid_argument);
  EXPECT_EQ(renderer.width(), 320);
  EXPECT_EQ(renderer.height(), 240);
  const Image after = render_box(renderer, box);
  EXPECT_TRUE(before.rgba == after.rgba);
}

}  // namespace
}  // namespace tumble::render
