// Design note: see render/renderer.hpp. This file wires the context, the uploaded meshes and
// the passes together; each pass lives in its own file.
#include "render/renderer.hpp"

#include <vector>

#include "gpu_mesh.hpp"
#include "overlay_pass.hpp"
#include "render/offscreen_context.hpp"
#include "scene_passes.hpp"

namespace tumble::render {

struct Renderer::Impl {
  explicit Impl(const RendererOptions& options)
      : context(options.width, options.height, options.samples) {}

  OffscreenContext context;
  std::vector<detail::GpuMesh> meshes;
  std::unique_ptr<detail::ScenePasses> scene;
  std::unique_ptr<detail::OverlayPass> overlay;  // created by the first frame with text
};

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {
  impl_->context.make_current();
  impl_->scene = std::make_unique<detail::ScenePasses>();
}

Renderer::~Renderer() {
  // GL objects go before the context that owns them.
  impl_->context.make_current();
  impl_->overlay.reset();
  impl_->scene.reset();
  for (detail::GpuMesh& mesh : impl_->meshes) detail::destroy_mesh(mesh);
}

MeshId Renderer::upload(const MeshData& mesh) {
  impl_->context.make_current();
  impl_->meshes.push_back(detail::upload_mesh(mesh));
  return MeshId{static_cast<std::uint32_t>(impl_->meshes.size() - 1)};
}

Image Renderer::render(const DrawList& frame) {
  Image image;
  render(frame, image);
  return image;
}

void Renderer::render(const DrawList& frame, Image& out) {
  OffscreenContext& context = impl_->context;
  context.make_current();
  impl_->scene->draw(frame, impl_->meshes, context);
  if (frame.has_overlays()) {
    if (!impl_->overlay) impl_->overlay = std::make_unique<detail::OverlayPass>();
    impl_->overlay->draw(frame, context.width(), context.height());
  }
  context.read_pixels(out);
}

int Renderer::width() const {
  return impl_->context.width();
}
int Renderer::height() const {
  return impl_->context.height();
}
int Renderer::samples() const {
  return impl_->context.samples();
}

}  // namespace tumble::render
