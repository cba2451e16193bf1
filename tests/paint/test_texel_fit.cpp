// Least-squares texel fit (paint/texel_fit.h) and pull-push fill (paint/padding.h): exact answers on
// code-built layouts (a texture that the new layout reproduces bilinearly, charts sharing texels,
// tiling UVs), the fit against point sampling and box downsizing in surface MSE, and the export
// options the fitted output is written with.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>
#include <tiny_gltf.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

#include "adaptex/adapt/texture_update.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/export.h"
#include "adaptex/paint/padding.h"
#include "adaptex/paint/texel_fit.h"
#include "adaptex/paint/texel_map.h"
#include "adaptex/param/unwrap.h"
#include "test_support.h"

using namespace adaptex;

namespace {

/// One wedge per vertex, one chart, uv = g(position).
Parameterization layout_of(const TriMesh& mesh, const std::function<Vec2(const Vec3&)>& g) {
  Parameterization p;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    p.uv.push_back(g(mesh.positions[v]));
    p.wedge_vertex.push_back(v);
  }
  p.uv_faces = mesh.faces;
  p.face_chart.assign(mesh.faces.size(), 0);
  p.num_charts = 1;
  return p;
}

/// A W x H image from a function of the texel centre (RGBA in [0,255]).
ImageRGBA8 image_of(int W, int H, const std::function<std::array<double, 4>(double, double)>& f) {
  ImageRGBA8 img(W, H);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const auto c = f((i + 0.5) / W, (j + 0.5) / H);
      for (int k = 0; k < 4; ++k) img.texel(i, j)[k] = static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0, 255.0)));
    }
  return img;
}

/// Surface MSE (RGB in [0,1], mean over area-uniform points) between two textures on two layouts.
double surface_mse(const TriMesh& mesh, const Parameterization& pa, const ImageRGBA8& ta,
                   const Parameterization& pb, const ImageRGBA8& tb, long long count = 100000) {
  const std::vector<SurfacePoint> pts = sample_surface(mesh, count, 7);
  double sum = 0;
  auto uv_at = [](const Parameterization& p, const SurfacePoint& s) {
    const Face& w = p.uv_faces[s.face];
    return Vec2(s.b0 * p.uv[w[0]] + s.b1 * p.uv[w[1]] + (1 - s.b0 - s.b1) * p.uv[w[2]]);
  };
  for (const SurfacePoint& s : pts) {
    const Vec2 a = uv_at(pa, s), b = uv_at(pb, s);
    sum += (sample_bilinear(ta, a.x(), a.y()) - sample_bilinear(tb, b.x(), b.y())).squaredNorm();
  }
  return sum / (3.0 * double(pts.size()));
}

/// Box downsizing by an integer factor (mean of each k x k block), as a user without adaptex does.
ImageRGBA8 box_down(const ImageRGBA8& img, int k) {
  ImageRGBA8 out(img.width / k, img.height / k);
  for (int j = 0; j < out.height; ++j)
    for (int i = 0; i < out.width; ++i)
      for (int c = 0; c < 4; ++c) {
        int s = 0;
        for (int b = 0; b < k; ++b)
          for (int a = 0; a < k; ++a) s += img.texel(i * k + a, j * k + b)[c];
        out.texel(i, j)[c] = static_cast<std::uint8_t>((s + k * k / 2) / (k * k));
      }
  return out;
}

int max_abs_diff(const ImageRGBA8& a, const ImageRGBA8& b) {
  int d = 0;
  for (size_t k = 0; k < a.data.size(); ++k) d = std::max(d, std::abs(int(a.data[k]) - int(b.data[k])));
  return d;
}

/// Random texels.
ImageRGBA8 random_image(int W, int H, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> d(0, 255);
  ImageRGBA8 img(W, H);
  for (auto& v : img.data) v = static_cast<std::uint8_t>(d(rng));
  return img;
}

/// \p T looked up bilinearly at the texel centres of a W x H image through uv -> g(uv).
ImageRGBA8 resample_through(const ImageRGBA8& T, int W, int H, const std::function<Vec2(double, double)>& g,
                            TextureAddress address = TextureAddress::ClampToEdge) {
  return image_of(W, H, [&](double u, double v) {
    const Vec2 q = g(u, v);
    return sample_bilinear_rgba(T, q.x(), q.y(), address);
  });
}

}  // namespace

// The original (48², identity) holds a 16² random texture looked up bilinearly through a mirror; the
// new layout is that mirror at 16², whose texel centres fall on original texel centres, so the
// original's reconstruction is exactly bilinear on the new grid: the fit returns the 16² texels.
TEST(TexelFit, ReproducesATextureThatIsBilinearOnTheNewLayout) {
  const TriMesh mesh = shapes::plane(6);
  const Parameterization old_layout = layout_of(mesh, [](const Vec3& p) { return Vec2(p.x(), p.y()); });
  const Parameterization mirrored = layout_of(mesh, [](const Vec3& p) { return Vec2(1 - p.x(), p.y()); });
  const ImageRGBA8 T = random_image(16, 16, 3);
  const ImageRGBA8 old_tex = resample_through(T, 48, 48, [](double u, double v) { return Vec2(1 - u, v); });
  TexelFitOptions exact;
  exact.anchor = 0;  // the pure least-squares answer
  const TexelFitResult r = fit_texels(mesh, old_layout, old_tex, mirrored, 16, 16, exact);
  EXPECT_LE(max_abs_diff(r.texture, T), 1);
  EXPECT_LE(r.residual, TexelFitOptions{}.tolerance);
  EXPECT_GT(r.samples, 16 * 16 * 4);
  for (bool c : r.coverage) EXPECT_TRUE(c);
}

// A hard-edged original (a disc and a diagonal edge) on a warped new layout at a third of the size:
// least squares beats point sampling (resample_texture) in surface MSE, and is much closer than it.
TEST(TexelFit, BeatsPointSamplingOnAHardEdgedTexture) {
  const TriMesh mesh = shapes::plane(12);
  const Parameterization old_layout = layout_of(mesh, [](const Vec3& p) { return Vec2(p.x(), p.y()); });
  const Parameterization warped = layout_of(mesh, [](const Vec3& p) {
    return Vec2(0.05 + 0.9 * std::pow(p.x(), 1.4), 0.05 + 0.9 * (p.y() + 0.15 * p.x() * (1 - p.y())) / 1.15);
  });
  const ImageRGBA8 old_tex = image_of(96, 96, [](double u, double v) {
    const bool disc = (u - 0.4) * (u - 0.4) + (v - 0.55) * (v - 0.55) < 0.06;
    const bool side = u + 0.3 * v > 0.8;
    return std::array<double, 4>{disc ? 230.0 : 20.0, side ? 200.0 : 40.0, disc != side ? 255.0 : 0.0, 255.0};
  });
  const TexelFitResult fit = fit_texels(mesh, old_layout, old_tex, warped, 32, 32);
  const ImageRGBA8 point = resample_texture(old_layout, old_tex, build_texel_map(mesh, warped, 32, 32), 4);
  const double e_fit = surface_mse(mesh, old_layout, old_tex, warped, fit.texture);
  const double e_point = surface_mse(mesh, old_layout, old_tex, warped, point);
  EXPECT_LT(e_fit, 0.9 * e_point) << "fit " << e_fit << ", point sampling " << e_point;
}

// The artist's own layout at a quarter of the size: the fit beats box downsizing, on a plane and on
// the multi-chart unwrap of a torus (charts with borders, a texture that is a function of 3-D position).
TEST(TexelFit, BeatsBoxDownsizingOnTheSameLayout) {
  const TriMesh plane = shapes::plane(8);
  const Parameterization id = layout_of(plane, [](const Vec3& p) { return Vec2(p.x(), p.y()); });
  const ImageRGBA8 tex = image_of(128, 128, [](double u, double v) {
    const double s = 127.5 + 127.5 * std::sin(40 * u * u + 9 * v);
    return std::array<double, 4>{s, u * v > 0.2 ? 220.0 : 30.0, 255 - s, 255.0};
  });
  const TexelFitResult fit = fit_resize(plane, id, tex, 32, 32);
  const double e_fit = surface_mse(plane, id, tex, id, fit.texture), e_box = surface_mse(plane, id, tex, id, box_down(tex, 4));
  EXPECT_LT(e_fit, 0.9 * e_box) << "fit " << e_fit << ", box " << e_box;

  const TriMesh torus = shapes::torus(48, 24);
  const Parameterization atlas = unwrap(torus).param;
  const TexelMap map = build_texel_map(torus, atlas, 256, 256);
  ImageRGBA8 ttex(256, 256, {255, 255, 255, 255});
  for (int t : map.inside) {
    const Vec3f& p = map.position[t];
    const bool stripe = std::fmod(std::abs(p.x() * 7 + p.z() * 3), 1.0) < 0.5;
    ttex.data[size_t(t) * 4 + 0] = stripe ? 210 : 30;
    ttex.data[size_t(t) * 4 + 1] = static_cast<std::uint8_t>(127 + 120 * std::sin(9 * p.y()));
    ttex.data[size_t(t) * 4 + 2] = 90;
  }
  apply_seam_padding(ttex, build_seam_padding(map, 4));
  const TexelFitResult tfit = fit_resize(torus, atlas, ttex, 64, 64);
  const double t_fit = surface_mse(torus, atlas, ttex, atlas, tfit.texture);
  const double t_box = surface_mse(torus, atlas, ttex, atlas, box_down(ttex, 4));
  EXPECT_LT(t_fit, 0.9 * t_box) << "fit " << t_fit << ", box " << t_box;
}

// A texel that only a sliver of the footprints touches (the column just past a chart's edge), where
// the original ramps up steeply: pure least squares extrapolates it far past the original's range
// (the speckles seen along real chart borders, which mip-mapping would spread); the default anchor
// pulls it back towards the original's colours under it.
TEST(TexelFit, AnchorKeepsSliverTexelsInRange) {
  const TriMesh mesh = shapes::plane(8);
  const Parameterization id = layout_of(mesh, [](const Vec3& p) { return Vec2(p.x(), p.y()); });
  const Parameterization chart = layout_of(mesh, [](const Vec3& p) { return Vec2(0.1 + 0.506 * p.x(), 0.1 + 0.8 * p.y()); });
  const ImageRGBA8 tex = image_of(64, 64, [](double u, double) {
    const double s = std::clamp((u - 0.85) / 0.15, 0.0, 1.0);
    return std::array<double, 4>{40 + 120 * s * s * (3 - 2 * s), 90, 90, 255};
  });
  auto brightest = [&](double anchor) {
    TexelFitOptions o;
    o.anchor = anchor;
    const TexelFitResult r = fit_texels(mesh, id, tex, chart, 16, 16, o);
    int m = 0;
    for (size_t t = 0; t < r.coverage.size(); ++t)
      if (r.coverage[t]) m = std::max<int>(m, r.texture.data[t * 4]);
    return m;
  };
  // The original's red never exceeds 160; the overshoot past it at least halves with the anchor.
  const int free_overshoot = brightest(0.0) - 160, anchored_overshoot = brightest(TexelFitOptions{}.anchor) - 160;
  EXPECT_GT(free_overshoot, 40);
  EXPECT_LE(2 * anchored_overshoot, free_overshoot);
}

// Two squares of areas 1 and 4 whose original charts hold colours a and b share one chart of the
// new layout, the larger one mirrored: every fitted texel is the area-weighted mean (a + 4b) / 5.
TEST(TexelFit, SharedChartsGetTheAreaWeightedCompromise) {
  TriMesh small = shapes::plane(4), big = shapes::plane(4, 2.0);
  for (Vec3& p : big.positions) p.x() += 3;
  const TriMesh mesh = shapes::disjoint_union({small, big});
  Parameterization old_layout = layout_of(mesh, [](const Vec3& p) {
    return p.x() < 2.5 ? Vec2(0.05 + 0.4 * p.x(), 0.05 + 0.9 * p.y()) : Vec2(0.55 + 0.2 * (p.x() - 3), 0.05 + 0.45 * p.y());
  });
  Parameterization shared = layout_of(mesh, [](const Vec3& p) {
    return p.x() < 2.5 ? Vec2(0.1 + 0.8 * p.x(), 0.1 + 0.8 * p.y()) : Vec2(0.9 - 0.4 * (p.x() - 3), 0.1 + 0.4 * p.y());
  });
  const ImageRGBA8 old_tex = image_of(64, 64, [](double u, double) {
    return u < 0.5 ? std::array<double, 4>{40, 200, 100, 255} : std::array<double, 4>{240, 0, 180, 255};
  });
  const TexelFitResult r = fit_texels(mesh, old_layout, old_tex, shared, 20, 20);
  const std::array<double, 4> expect{(40 + 4 * 240) / 5.0, (200 + 0) / 5.0, (100 + 4 * 180) / 5.0, 255};
  int covered = 0;
  for (size_t t = 0; t < r.coverage.size(); ++t) {
    if (!r.coverage[t]) continue;
    ++covered;
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(r.texture.data[t * 4 + c], expect[c], 1.0) << "texel " << t;
  }
  EXPECT_GT(covered, 16 * 16);
  EXPECT_LT(covered, 20 * 20);  // the border ring is outside every footprint
}

// UVs that tile twice over the original (a 16² texture, Repeat) and a 32² new layout (Repeat):
// the new texels are the tile repeated, the wrap-around footprints included.
TEST(TexelFit, RepeatAddressingReproducesATiledTexture) {
  const TriMesh mesh = shapes::plane(5);
  const Parameterization tiled = layout_of(mesh, [](const Vec3& p) { return Vec2(2 * p.x() - 0.5, 2 * p.y() + 1); });
  const Parameterization id = layout_of(mesh, [](const Vec3& p) { return Vec2(p.x(), p.y()); });
  const ImageRGBA8 tile = random_image(16, 16, 11);
  TexelFitOptions opt;
  opt.source_address = opt.address = TextureAddress::Repeat;
  opt.anchor = 0;  // the pure least-squares answer
  const TexelFitResult r = fit_texels(mesh, tiled, tile, id, 32, 32, opt);
  const ImageRGBA8 expect = resample_through(tile, 32, 32, [](double u, double v) { return Vec2(2 * u - 0.5, 2 * v + 1); },
                                             TextureAddress::Repeat);
  EXPECT_LE(max_abs_diff(r.texture, expect), 1);
}

TEST(TexelFit, RejectsBadInputAndCancels) {
  const TriMesh mesh = shapes::plane(3);
  const Parameterization id = layout_of(mesh, [](const Vec3& p) { return Vec2(p.x(), p.y()); });
  const ImageRGBA8 tex(8, 8, {9, 9, 9, 255});
  Parameterization short_layout = id;
  short_layout.uv_faces.pop_back();
  EXPECT_THROW(fit_texels(mesh, short_layout, tex, id, 4, 4), InvalidInputError);
  Parameterization nan_layout = id;
  nan_layout.uv[2].x() = std::nan("");
  EXPECT_THROW(fit_texels(mesh, id, tex, nan_layout, 4, 4), InvalidInputError);
  EXPECT_THROW(fit_texels(mesh, id, tex, id, 0, 4), InvalidInputError);
  EXPECT_THROW(fit_texels(mesh, id, tex, id, 8192, 4097), InvalidInputError);
  TexelFitOptions negative;
  negative.anchor = -1;
  EXPECT_THROW(fit_texels(mesh, id, tex, id, 4, 4, negative), InvalidInputError);
  EXPECT_THROW(fit_texels(mesh, id, ImageRGBA8(), id, 4, 4), InvalidInputError);
  TexelFitOptions opt;
  opt.progress = [](std::string_view, double) { return false; };
  EXPECT_THROW(fit_texels(mesh, id, tex, id, 4, 4, opt), CancelledError);
  // A constant texture fits to the constant on every covered texel, and the fill keeps it.
  const TexelFitResult r = fit_texels(mesh, id, tex, id, 5, 7);
  for (size_t k = 0; k < r.texture.data.size(); ++k) EXPECT_EQ(r.texture.data[k], k % 4 == 3 ? 255 : 9);
}

// Several maps of one material: one fitter, the same result as the one-shot fit.
TEST(TexelFit, FitterIsReusableAcrossMaps) {
  const TriMesh mesh = shapes::plane(4);
  const Parameterization id = layout_of(mesh, [](const Vec3& p) { return Vec2(p.x(), p.y()); });
  const Parameterization half = layout_of(mesh, [](const Vec3& p) { return Vec2(0.1 + 0.506 * p.x(), 0.2 + 0.6 * p.y()); });
  const ImageRGBA8 a = random_image(32, 32, 1), b = random_image(32, 32, 2);
  const TexelFitter fitter(mesh, id, 32, 32, half, 16, 16);
  EXPECT_EQ(fitter.fit(a).texture.data, fit_texels(mesh, id, a, half, 16, 16).texture.data);
  EXPECT_EQ(fitter.fit(b).texture.data, fit_texels(mesh, id, b, half, 16, 16).texture.data);
  int covered = 0;
  for (bool c : fitter.coverage()) covered += c;
  EXPECT_GT(covered, 8 * 9);
  EXPECT_LT(covered, 16 * 16);
}

// The result does not depend on the thread count (fixed sample order and summation blocks), and a
// sample cap at a quarter of the default densities (the original prefiltered to match) still beats
// box downsizing on white noise, the worst case for aliasing.
TEST(TexelFit, DeterministicAcrossThreadCountsAndCapped) {
  const TriMesh mesh = shapes::torus(40, 20);
  const Parameterization atlas = unwrap(mesh).param;
  const ImageRGBA8 tex = random_image(128, 128, 5);
  TexelFitResult one, two;
  tbb::task_arena(1).execute([&] { one = fit_resize(mesh, atlas, tex, 32, 32); });
  tbb::task_arena(2).execute([&] { two = fit_resize(mesh, atlas, tex, 32, 32); });
  EXPECT_EQ(one.texture.data, two.texture.data);
  EXPECT_EQ(one.iterations, two.iterations);
  TexelFitOptions capped;
  capped.max_samples = one.samples / 4;
  const TexelFitResult c = fit_resize(mesh, atlas, tex, 32, 32, capped);
  EXPECT_LE(c.samples, capped.max_samples);
  EXPECT_GT(c.samples, capped.max_samples / 2);
  EXPECT_LT(surface_mse(mesh, atlas, tex, atlas, c.texture), surface_mse(mesh, atlas, tex, atlas, box_down(tex, 4)));
}

// Pull-push: covered texels keep their bytes; uncovered ones take convex mixtures of the covered
// colours (never the white they held); a one-colour chart fills the whole image with its colour.
TEST(PullPushFill, DilatesTheCoveredColours) {
  ImageRGBA8 img(37, 23, {255, 255, 255, 255});
  std::vector<bool> cov(37 * 23, false);
  for (int j = 3; j < 12; ++j)
    for (int i = 5; i < 14; ++i) {
      cov[j * 37 + i] = true;
      std::uint8_t* px = img.texel(i, j);
      px[0] = static_cast<std::uint8_t>(10 + 5 * i);
      px[1] = 0;
      px[2] = static_cast<std::uint8_t>(100 + j);
      px[3] = 255;
    }
  const ImageRGBA8 before = img;
  pull_push_fill(img, cov);
  for (int t = 0; t < 37 * 23; ++t) {
    if (cov[t]) {
      for (int c = 0; c < 4; ++c) EXPECT_EQ(img.data[t * 4 + c], before.data[t * 4 + c]);
      continue;
    }
    EXPECT_GE(img.data[t * 4 + 0], 35);
    EXPECT_LE(img.data[t * 4 + 0], 75);
    EXPECT_EQ(img.data[t * 4 + 1], 0) << "texel " << t;
    EXPECT_GE(img.data[t * 4 + 2], 103);
    EXPECT_LE(img.data[t * 4 + 2], 111);
  }
  // Left to right, the fill keeps the chart's gradient direction (not a flat colour).
  EXPECT_LT(img.texel(0, 20)[0], img.texel(36, 20)[0]);

  ImageRGBA8 one(16, 9, {255, 255, 255, 0});
  std::vector<bool> c1(16 * 9, false);
  c1[4 * 16 + 11] = true;
  std::copy_n(std::array<std::uint8_t, 4>{12, 34, 56, 255}.data(), 4, one.texel(11, 4));
  pull_push_fill(one, c1);
  for (int t = 0; t < 16 * 9; ++t) EXPECT_EQ(std::vector<std::uint8_t>(one.data.begin() + t * 4, one.data.begin() + t * 4 + 4),
                                             (std::vector<std::uint8_t>{12, 34, 56, 255}));
  EXPECT_THROW(pull_push_fill(one, std::vector<bool>(3)), InvalidInputError);
}

// The sampler option of the .glb and the MTL's -clamp; the defaults are as before.
TEST(TexelFitExport, SamplerWrapAndMtlClamp) {
  const TriMesh mesh = shapes::plane(2);
  const Parameterization id = layout_of(mesh, [](const Vec3& p) { return Vec2(p.x(), p.y()); });
  const ImageRGBA8 tex(4, 4, {1, 2, 3, 255});
  auto wrap_of = [&](const ExportOptions& o) {
    const std::vector<unsigned char> glb = encode_glb(mesh, id, tex, o);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    EXPECT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), static_cast<unsigned>(glb.size()))) << err;
    EXPECT_EQ(model.samplers.size(), 1u);
    EXPECT_EQ(model.samplers[0].wrapS, model.samplers[0].wrapT);
    return model.samplers[0].wrapS;
  };
  EXPECT_EQ(wrap_of(ExportOptions{}), TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE);
  ExportOptions rep;
  rep.wrap = TextureAddress::Repeat;
  EXPECT_EQ(wrap_of(rep), TINYGLTF_TEXTURE_WRAP_REPEAT);

  const test::TempDir tmp;
  const std::filesystem::path& dir = tmp.path;
  auto read = [](const std::filesystem::path& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  };
  write_mtl(dir / "a.mtl", "m", "a.png");
  write_mtl(dir / "b.mtl", "m", "b.png", true);
  EXPECT_NE(read(dir / "a.mtl").find("\nmap_Kd a.png\n"), std::string::npos);
  EXPECT_NE(read(dir / "b.mtl").find("\nmap_Kd -clamp on b.png\n"), std::string::npos);
}
