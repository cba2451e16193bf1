/// \file material_generate.cpp
/// The generated layered material (`strokes generate --kind material`): three layers whose paths
/// come from the version 1 generator, with channels, a mask and pen pressure added.
#include "adaptex/paint/material_generate.h"

#include <cmath>
#include <numbers>

#include "adaptex/paint/generate.h"
#include "splitmix.h"

namespace adaptex {

namespace {

using detail::Rng;

/// The paths of a version 1 set of \p kind (its radius, hardness, opacity and dabs).
std::vector<Stroke> paths(const TriMesh& mesh, StrokeKind kind, int count, std::uint64_t seed) {
  GenerateOptions opt;
  opt.kind = kind;
  opt.count = count;
  opt.seed = seed;
  return generate_strokes(mesh, opt).strokes;
}

MaterialStroke brush_from(const Stroke& s) {
  MaterialStroke m;
  m.radius = s.radius;
  m.hardness = s.hardness;
  m.opacity = s.opacity;
  m.dabs = s.dabs;
  return m;
}

MaterialStroke fill(unsigned channels, const MaterialValue& value) {
  MaterialStroke m;
  m.type = MaterialStroke::Type::Fill;
  m.channels = channels;
  m.value = value;
  return m;
}

void set_color(MaterialValue& v, const Vec3& c) {
  for (int k = 0; k < 3; ++k) v[k] = c[k];
}

/// The "Base" layer's first stroke: a fill of a muted colour and roughness 0.55-0.8.
MaterialLayer flat_base(Rng& rng) {
  MaterialLayer layer;
  layer.name = "Base";
  MaterialValue v{};
  set_color(v, Vec3(rng.uniform(0.35, 0.7), rng.uniform(0.3, 0.6), rng.uniform(0.25, 0.5)));
  v[channel_offset(Channel::Roughness)] = rng.uniform(0.55, 0.8);
  layer.strokes.push_back(fill(channel_bit(Channel::BaseColor) | channel_bit(Channel::Roughness), v));
  return layer;
}

MaterialLayer base_layer(const TriMesh& mesh, Rng& rng, std::uint64_t seed) {
  MaterialLayer layer = flat_base(rng);
  for (const Stroke& s : paths(mesh, StrokeKind::Blobs, 6, seed)) {
    MaterialStroke m = brush_from(s);
    m.channels = channel_bit(Channel::BaseColor) | channel_bit(Channel::Roughness);
    set_color(m.value, s.color);
    m.value[channel_offset(Channel::Roughness)] = rng.uniform(0.4, 0.9);
    layer.strokes.push_back(std::move(m));
  }
  return layer;
}

MaterialLayer metal_layer(const TriMesh& mesh, Rng& rng, std::uint64_t seed) {
  MaterialLayer layer;
  layer.name = "Metal";
  layer.mask = LayerMask{0.0, {}};
  for (const Stroke& s : paths(mesh, StrokeKind::Blobs, 3, seed)) {
    MaterialStroke m = brush_from(s);
    m.mask_value = 1;
    layer.mask->strokes.push_back(std::move(m));
  }
  MaterialValue v{};
  const double grey = rng.uniform(0.6, 0.85);
  set_color(v, Vec3(grey, grey, grey * rng.uniform(0.9, 1.0)));
  v[channel_offset(Channel::Metallic)] = 1;
  v[channel_offset(Channel::Roughness)] = rng.uniform(0.15, 0.35);
  layer.strokes.push_back(
      fill(channel_bit(Channel::BaseColor) | channel_bit(Channel::Metallic) | channel_bit(Channel::Roughness), v));
  return layer;
}

/// What the scratch layer's strokes paint: alternately height (with a dark colour) and roughness, or
/// one channel only.
enum class ScratchChannels { Alternate, Roughness, Height };

MaterialLayer scratch_layer(const TriMesh& mesh, Rng& rng, std::uint64_t seed,
                            ScratchChannels which = ScratchChannels::Alternate) {
  MaterialLayer layer;
  layer.name = "Scratches";
  layer.opacity = which == ScratchChannels::Alternate ? rng.uniform(0.85, 1.0) : 1.0;
  const std::vector<Stroke> lines = paths(mesh, StrokeKind::Lines, 40, seed);
  for (size_t k = 0; k < lines.size(); ++k) {
    MaterialStroke m = brush_from(lines[k]);
    const size_t n = m.dabs.size();
    for (size_t i = 0; i < n; ++i)  // a pen stroke: light at both ends, firm in the middle
      m.pressure.push_back(0.2 + 0.8 * std::sin(std::numbers::pi * (i + 0.5) / n));
    m.radius_curve.points = {Vec2(0, 0.3), Vec2(1, 1)};
    m.opacity_curve.points = {Vec2(0, 0.4), Vec2(0.5, 1), Vec2(1, 1)};
    const bool height = which == ScratchChannels::Alternate ? k % 2 == 0 : which == ScratchChannels::Height;
    if (height) {
      m.channels = channel_bit(Channel::Height);
      m.value[channel_offset(Channel::Height)] = rng.uniform(0.2, 0.35);
      // An engraving alone has a profile (hardness 0: its slope spans the radius). A hard step's normal
      // is a line of infinite slope that no normal map holds at any size (docs/quality.md).
      if (which == ScratchChannels::Height) m.hardness = 0;
      if (which == ScratchChannels::Alternate) {
        m.channels |= channel_bit(Channel::BaseColor);
        const double dark = rng.uniform(0.1, 0.3);
        set_color(m.value, Vec3(dark, dark, dark));
      }
    } else {
      m.channels = channel_bit(Channel::Roughness);
      m.value[channel_offset(Channel::Roughness)] = rng.uniform(0.05, 0.2);
    }
    layer.strokes.push_back(std::move(m));
  }
  if (which != ScratchChannels::Alternate) return layer;
  MaterialStroke erase = brush_from(lines.front());  // cut the first engraving short
  erase.type = MaterialStroke::Type::Erase;
  erase.channels = channel_bit(Channel::Height);
  erase.dabs.resize((erase.dabs.size() + 1) / 2);
  erase.radius *= 1.5;
  erase.hardness = 1;
  layer.strokes.push_back(std::move(erase));
  return layer;
}

}  // namespace

MaterialStrokeFile generate_material_strokes(const TriMesh& mesh, std::uint64_t seed) {
  Rng rng{seed ^ 0x6d6174657269616cULL};  // "material": a stream of its own
  MaterialStrokeFile file;
  file.height_scale = 0.005 * bounding_box(mesh).diagonal();
  file.layers.push_back(base_layer(mesh, rng, seed * 3 + 1));
  file.layers.push_back(metal_layer(mesh, rng, seed * 3 + 2));
  file.layers.push_back(scratch_layer(mesh, rng, seed * 3 + 3));
  return file;
}

MaterialStrokeFile generate_material_detail(const TriMesh& mesh, MaterialDetail detail, std::uint64_t seed) {
  Rng rng{seed ^ 0x64657461696cULL};  // "detail": a stream of its own
  MaterialStrokeFile file;
  file.height_scale = 0.005 * bounding_box(mesh).diagonal();
  file.layers.push_back(flat_base(rng));
  file.layers.push_back(scratch_layer(mesh, rng, seed * 3 + 3,
                                      detail == MaterialDetail::HeightEngravings ? ScratchChannels::Height
                                                                       : ScratchChannels::Roughness));
  return file;
}

}  // namespace adaptex
