#include "fxaa_pass.hpp"

#include <stdexcept>

#include "fxaa_shaders.hpp"
#include "render/offscreen_context.hpp"

namespace tumble::render::detail {

FxaaPass::FxaaPass(int width, int height)
    : blocks_program_("fxaa edge blocks", shaders::kFxaaVertex, shaders::kEdgeBlocksFragment),
      filter_program_("fxaa", shaders::kEdgeBlockPoints, shaders::kFxaaFragment),
      empty_(GlVertexArray::create()),
      blocks_(GlTexture::create()),
      blocks_fbo_(GlFramebuffer::create()),
      blocks_width_((width + 7) / 8),
      blocks_height_((height + 7) / 8) {
  glBindTexture(GL_TEXTURE_2D, blocks_.get());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, blocks_width_, blocks_height_, 0, GL_RED, GL_UNSIGNED_BYTE,
               nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, blocks_fbo_.get());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, blocks_.get(), 0);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) throw std::runtime_error("renderer: the fxaa block framebuffer is incomplete");
}

void FxaaPass::apply(OffscreenContext& context) {
  const float texel[2] = {1.0f / static_cast<float>(context.width()),
                          1.0f / static_cast<float>(context.height())};
  context.copy_scene_to_output();  // what the filter leaves alone (it discards flat pixels)
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDepthMask(GL_FALSE);
  glBindVertexArray(empty_.get());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, context.scene_texture());

  // Edge blocks.
  glBindFramebuffer(GL_FRAMEBUFFER, blocks_fbo_.get());
  glViewport(0, 0, blocks_width_, blocks_height_);
  blocks_program_.use();
  glUniform1i(blocks_program_.uniform("scene"), 0);
  glUniform2fv(blocks_program_.uniform("texel"), 1, texel);
  glDrawArrays(GL_TRIANGLES, 0, 3);

  // The filter, into the output.
  context.set_target(OffscreenContext::Target::output);
  context.make_current();
  filter_program_.use();
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, blocks_.get());
  glUniform1i(filter_program_.uniform("scene"), 0);
  glUniform1i(filter_program_.uniform("blocks"), 1);
  glUniform2fv(filter_program_.uniform("texel"), 1, texel);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glDrawArrays(GL_POINTS, 0, blocks_width_ * blocks_height_);
  glDisable(GL_PROGRAM_POINT_SIZE);

  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
}

}  // namespace tumble::render::detail
