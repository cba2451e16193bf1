#pragma once
/// \file texel_fit_fixture.h
/// A textured asset built in code for the texel-fit benchmark and quality tool: a torus with its
/// unwrap() atlas and two "maps" painted as functions of 3-D position (hard-edged stripes and dots
/// over smooth shading; a bumpy data map), seam-padded by 4 texels as a painter would.
#include <cmath>

#include "adaptex/core/image.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/padding.h"
#include "adaptex/paint/texel_map.h"
#include "adaptex/param/unwrap.h"

namespace adaptex::bench {

struct TexturedFixture {
  TriMesh mesh;
  Parameterization param;
  ImageRGBA8 diffuse, data;
};

/// shapes::torus(major, minor) (2 major minor faces), its unwrap() layout, two size² maps.
inline TexturedFixture textured_torus(int major, int minor, int size) {
  TexturedFixture f;
  f.mesh = shapes::torus(major, minor);
  f.param = unwrap(f.mesh).param;
  const TexelMap map = build_texel_map(f.mesh, f.param, size, size);
  f.diffuse = ImageRGBA8(size, size, {255, 255, 255, 255});
  f.data = ImageRGBA8(size, size, {255, 255, 255, 255});
  for (int t : map.inside) {
    const Vec3f& p = map.position[t];
    const double stripe = std::fmod(std::abs(5.0 * p.x() + 2.0 * p.z() + 9.0), 1.0) < 0.35 ? 1 : 0;
    const double dots = std::sin(40 * p.x()) * std::sin(40 * p.y()) * std::sin(40 * p.z()) > 0.5 ? 1 : 0;
    const double shade = 0.5 + 0.5 * std::sin(3 * p.y() + 2 * p.x());
    std::uint8_t* d = f.diffuse.data.data() + static_cast<size_t>(t) * 4;
    d[0] = static_cast<std::uint8_t>(std::lround(40 + 170 * stripe + 40 * shade * (1 - stripe)));
    d[1] = static_cast<std::uint8_t>(std::lround(60 + 150 * shade - 50 * dots));
    d[2] = static_cast<std::uint8_t>(std::lround(200 * dots + 50 * (1 - dots) * shade));
    std::uint8_t* g = f.data.data.data() + static_cast<size_t>(t) * 4;
    g[0] = g[1] = g[2] = static_cast<std::uint8_t>(std::lround(127.5 + 127 * std::sin(25 * p.x() + 13 * p.z())));
  }
  const SeamPadding pad = build_seam_padding(map, 4);
  apply_seam_padding(f.diffuse, pad);
  apply_seam_padding(f.data, pad);
  return f;
}

}  // namespace adaptex::bench
