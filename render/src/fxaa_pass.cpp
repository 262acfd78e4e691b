#include "fxaa_pass.hpp"

#include <algorithm>

#include "fxaa_shaders.hpp"
#include "render/offscreen_context.hpp"

namespace tumble::render::detail {

FxaaPass::FxaaPass(int width, int height)
    : filter_program_("fxaa", shaders::kEdgeBlockVertex, shaders::kFxaaFragment),
      rectangles_(GlVertexArray::create()),
      rectangle_buffer_(GlBuffer::create()),
      width_(width),
      height_(height) {
  glBindVertexArray(rectangles_.get());
  glBindBuffer(GL_ARRAY_BUFFER, rectangle_buffer_.get());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
}

void FxaaPass::apply(OffscreenContext& context, const std::optional<PixelBox>& drawn,
                     const std::vector<PixelBox>* copied) {
  // The scene as drawn (bottom-up rows: the blocks are found in GL's own coordinates), within
  // the box where anything was drawn; its corner is on the blocks' grid.
  const PixelBox box = drawn.value_or(PixelBox{0, 0, width_, height_});
  const int box_width = std::max(0, std::min(box.x1, width_) - box.x0);
  const int box_height = std::max(0, std::min(box.y1, height_) - box.y0);
  runs_.clear();
  if (box_width > 0 && box_height > 0) {
    scene_.resize(4 * static_cast<std::size_t>(box_width) * static_cast<std::size_t>(box_height));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(box.x0, box.y0, box_width, box_height, GL_RGBA, GL_UNSIGNED_BYTE, scene_.data());
    find_edge_blocks(scene_.data(), box_width, box_height, runs_);
    for (BlockRun& run : runs_) {
      run.row += box.y0 / kEdgeBlock;
      run.first += box.x0 / kEdgeBlock;
    }
  }
  corners_.clear();
  edge_blocks_ = 0;
  for (const BlockRun& run : runs_) {
    const auto x0 = static_cast<float>(run.first * kEdgeBlock);
    const auto x1 = static_cast<float>(std::min(width_, (run.first + run.count) * kEdgeBlock));
    const auto y0 = static_cast<float>(run.row * kEdgeBlock);
    const auto y1 = static_cast<float>(std::min(height_, (run.row + 1) * kEdgeBlock));
    corners_.insert(corners_.end(), {x0, y0, x1, y0, x1, y1, x0, y0, x1, y1, x0, y1});
    edge_blocks_ += run.count;
  }

  // What the filter leaves alone (it discards flat pixels).
  if (copied != nullptr) {
    for (const PixelBox& part : *copied)
      context.copy_scene_box_to_output(part.x0, part.y0, part.x1, part.y1);
  } else {
    context.copy_scene_to_output();
  }
  context.set_target(OffscreenContext::Target::output);
  context.make_current();
  if (corners_.empty()) return;
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDepthMask(GL_FALSE);
  glBindVertexArray(rectangles_.get());
  glBindBuffer(GL_ARRAY_BUFFER, rectangle_buffer_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(corners_.size() * sizeof(float)),
               corners_.data(), GL_STREAM_DRAW);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, context.scene_texture());
  filter_program_.use();
  const float texel[2] = {1.0f / static_cast<float>(width_), 1.0f / static_cast<float>(height_)};
  glUniform1i(filter_program_.uniform("scene"), 0);
  glUniform2fv(filter_program_.uniform("texel"), 1, texel);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(corners_.size() / 2));
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
}

}  // namespace tumble::render::detail
