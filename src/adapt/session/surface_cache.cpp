// PaintSession: textures from the surface signal cache (PaintSessionOptions::surface_cache).
#include "session_impl.h"

namespace adaptex {

bool PaintSession::Impl::uses_surface_cache() const {
  return surface_fits && base_param && opt.update == TextureUpdate::Replay && !exact_only &&
         coverage >= opt.surface_cache_coverage && !history.strokes.empty();
}

SurfaceSignalCache& PaintSession::Impl::surface_cache_now() {
  if (!surface)
    surface = std::make_unique<SurfaceSignalCache>(mesh, texel_spacing / opt.surface_cache, history.background,
                                                   kMaxSurfaceCacheSamples);
  surface->update(history);
  return *surface;
}

const ImageRGBA8& PaintSession::Impl::texture_from_cache(Painter& p, const TriMesh& m, const std::vector<int>* parent_face) {
  p.fill_colours(surface_cache_now().texel_colours(p.texel_map(), m, parent_face));
  return p.texture();
}

}  // namespace adaptex
