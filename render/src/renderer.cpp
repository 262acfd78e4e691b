// Design note: see render/renderer.hpp. This file wires the context, the uploaded meshes and
// the passes together; each pass lives in its own file.
#include "render/renderer.hpp"

#include <vector>

#include "fxaa_pass.hpp"
#include "gpu_mesh.hpp"
#include "overlay_pass.hpp"
#include "render/offscreen_context.hpp"
#include "scene_passes.hpp"

namespace tumble::render {

struct Renderer::Impl {
  explicit Impl(const RendererOptions& options)
      : context(
            options.width, options.height, options.samples,
            /*post_process=*/options.filter != AntialiasingFilter::none && options.samples <= 1),
        lod(options.lod),
        filter_drawn_region(options.filter_drawn_region) {}

  OffscreenContext context;
  bool lod = true;
  bool filter_drawn_region = true;
  std::vector<detail::GpuMesh> meshes;
  std::unique_ptr<detail::ScenePasses> scene;
  std::unique_ptr<detail::FxaaPass> fxaa;        // when the context has a post-process
  std::unique_ptr<detail::OverlayPass> overlay;  // created by the first frame with text
  /// The output holds the stored layers of this generation (0: not known to) outside the
  /// boxes `written`, where the last frame drew (its scene's drawn box and its overlay).
  std::uint64_t output_layers = 0;
  std::vector<detail::PixelBox> written;
  std::vector<detail::PixelBox> copied;  // this frame's boxes to copy from the scene
};

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {
  impl_->context.make_current();
  // Lines carry their own coverage whenever the frame is anti-aliased at all.
  const bool smooth_lines = options.filter != AntialiasingFilter::none || options.samples > 1;
  impl_->scene =
      std::make_unique<detail::ScenePasses>(options.lod, options.reuse_static_layers, smooth_lines);
  if (impl_->context.has_post_process())
    impl_->fxaa = std::make_unique<detail::FxaaPass>(options.width, options.height);
}

Renderer::~Renderer() {
  // GL objects go before the context that owns them.
  impl_->context.make_current();
  impl_->overlay.reset();
  impl_->fxaa.reset();
  impl_->scene.reset();
  impl_->meshes.clear();
}

MeshId Renderer::upload(const MeshData& mesh) {
  impl_->context.make_current();
  impl_->meshes.push_back(detail::upload_mesh(mesh, impl_->lod));
  return MeshId{static_cast<std::uint32_t>(impl_->meshes.size() - 1)};
}

std::size_t Renderer::mesh_count() const {
  return impl_->meshes.size();
}

void Renderer::release_meshes(std::size_t keep) {
  if (keep >= impl_->meshes.size()) return;
  impl_->context.make_current();
  impl_->meshes.erase(impl_->meshes.begin() + static_cast<std::ptrdiff_t>(keep),
                      impl_->meshes.end());
}

Image Renderer::render(const DrawList& frame) {
  Image image;
  render(frame, image);
  return image;
}

void Renderer::render(const DrawList& frame, Image& out) {
  render(frame, out, ExtraPass{});
}

void Renderer::render(const DrawList& frame, Image& out, const ExtraPass& extra) {
  OffscreenContext& context = impl_->context;
  context.set_target(OffscreenContext::Target::scene);
  context.make_current();
  impl_->scene->draw(frame, impl_->meshes, context);
  // Later draws and the read-back: the output.
  const std::uint64_t layers = impl_->filter_drawn_region ? impl_->scene->started_from_layers() : 0;
  const std::optional<detail::PixelBox>& drawn = impl_->scene->drawn_box();
  if (impl_->fxaa) {
    // Where the output differs from this frame's scene: the last frame's drawn boxes and this
    // one's, when both drew over the same stored layers; else anywhere. As rectangles that do
    // not overlap: the boxes overlap mostly (the default demo's three held 949,000 pixels, more
    // than the frame's 921,600), and a pixel copied twice is copied for nothing.
    const bool partial = layers != 0 && drawn && layers == impl_->output_layers;
    if (partial) {
      impl_->written.push_back(*drawn);
      impl_->copied = detail::disjoint_cover(impl_->written);
    }
    impl_->fxaa->apply(context, impl_->filter_drawn_region ? drawn : std::nullopt,
                       partial ? &impl_->copied : nullptr);
    impl_->output_layers = drawn ? layers : 0;
    impl_->written.assign(1, drawn.value_or(detail::PixelBox{}));
  }
  if (frame.has_overlays()) {
    if (!impl_->overlay) impl_->overlay = std::make_unique<detail::OverlayPass>();
    if (impl_->fxaa && impl_->filter_drawn_region) {
      // The output holds the stored layers outside the scene's drawn box (the filter keeps to
      // it), so the panels' decorations may be stored over them.
      impl_->overlay->draw(frame, context.width(), context.height(), context, {layers, drawn});
    } else {
      impl_->overlay->draw(frame, context.width(), context.height());
    }
    const std::vector<detail::PixelBox>& boxes = impl_->overlay->last_boxes();
    impl_->written.insert(impl_->written.end(), boxes.begin(), boxes.end());
  }
  if (extra.before != nullptr) {
    context.read_pixels(*extra.before);
    context.make_current();  // the readback may have bound the resolve target
  }
  if (extra.draw) {
    extra.draw(context.width(), context.height());
    impl_->output_layers = 0;  // drawn anywhere
  }
  // Without a post-process, the overlay and the extra pass drew into the scene's framebuffer.
  if (!impl_->fxaa && (frame.has_overlays() || extra.draw)) impl_->scene->drawn_over();
  context.read_pixels(out);
}

void Renderer::with_context(const std::function<void()>& work) {
  impl_->context.make_current();
  work();
}

void Renderer::resize(int width, int height) {
  OffscreenContext& context = impl_->context;
  if (width == context.width() && height == context.height()) return;
  const int old_width = context.width();
  const int old_height = context.height();
  context.resize(width, height);  // checks the size; keeps the old one when it throws
  impl_->output_layers = 0;
  if (!impl_->fxaa) return;
  try {
    impl_->fxaa = std::make_unique<detail::FxaaPass>(width, height);
  } catch (...) {
    context.resize(old_width, old_height);  // the old pass still fits the old size
    throw;
  }
  context.make_current();
}

int Renderer::width() const {
  return impl_->context.width();
}
int Renderer::height() const {
  return impl_->context.height();
}
std::size_t Renderer::last_frame_triangles() const {
  return impl_->scene->last_frame_triangles();
}

int Renderer::samples() const {
  return impl_->context.samples();
}
AntialiasingFilter Renderer::filter() const {
  return impl_->fxaa ? AntialiasingFilter::fxaa : AntialiasingFilter::none;
}

}  // namespace tumble::render
