/// \file painter.cpp
/// §3.4 stroke sampling on the CPU: every dab is evaluated exactly (stroke-file
/// contract) at the 3-D point of each texel it can touch; the texels are found
/// through a Morton-sorted grid of texel points (texel_grid.h), never by
/// scanning the texture. Per-stroke maximum coverage is kept in a per-texel
/// alpha plus the colour under the open stroke, so the stored colour always
/// equals the contract at the texel centre.
#include "adaptex/paint/painter.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/paint/padding.h"
#include "texel_grid.h"
#include "adaptex/paint/decal.h"

namespace adaptex {

namespace {

inline float falloff_f(float t, float h) {
  if (t <= h)
    return 1.0f;
  if (t >= 1.0f)
    return 0.0f;
  const float s = (t - h) / (1.0f - h);
  return 1.0f - s * s * (3.0f - 2.0f * s);
}

/// round(255 v) for v clamped to [0,1] (half up, like lround on non-negative
/// values).
inline std::uint8_t to8(float v) {
  return static_cast<std::uint8_t>(
      static_cast<int>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f));
}

struct Rect {
  int i0 = 1 << 30, j0 = 1 << 30, i1 = -1, j1 = -1;
  void add(int i, int j) {
    i0 = std::min(i0, i);
    j0 = std::min(j0, j);
    i1 = std::max(i1, i);
    j1 = std::max(j1, j);
  }
  void add(const Rect &r) {
    if (r.i1 < r.i0)
      return;
    add(r.i0, r.j0);
    add(r.i1, r.j1);
  }
  bool empty() const { return i1 < i0; }
};

} // namespace

struct Painter::Impl {
  const TriMesh &mesh;
  const Parameterization &param;
  PainterOptions options;
  Vec3 background;
  TexelMap map;
  std::unique_ptr<detail::TexelGrid> grid;
  SeamPadding padding;
  std::vector<std::uint32_t> slot_ij; // slot -> i | j << 16
  std::vector<int> slot_texel;        // slot -> j*W+i
  std::vector<int> texel_slot;        // j*W+i -> slot, -1 outside the charts
  // Shared texels (TexelMap::aliases): the index holds their other surface points too, and
  // point_slot maps an index point to its texel's slot. Empty (the identity) without aliases.
  std::vector<int> point_slot;
  std::vector<std::array<float, 3>> colour, base;
  std::vector<float> alpha; // coverage of the open stroke, 0 elsewhere
  std::vector<int> touched; // slots with alpha > 0
  bool open = false;
  float col[3] = {0, 0, 0};
  float radius = 0, hardness = 0, opacity = 0;
  ImageRGBA8 tex;
  Rect dirty;
  bool painted = false;
  long long updates = 0;
  std::unique_ptr<DecalProjector> projector;

  Impl(const TriMesh &m, const Parameterization &p, const PainterOptions &o,
       const Vec3 &bg)
      : mesh(m), param(p), options(o), background(bg) {
    if (o.width <= 0 || o.height <= 0 || o.width > kMaxTextureSize || o.height > kMaxTextureSize)
      throw InvalidInputError(
          "painter: texture size must be in [1, " + std::to_string(kMaxTextureSize) + "] (got " +
          std::to_string(o.width) + "x" + std::to_string(o.height) + ")");
    if (o.padding < 0)
      throw InvalidInputError("painter: padding must be >= 0 (got " +
                              std::to_string(o.padding) + ")");
    if (!bg.allFinite() || bg.minCoeff() < 0 || bg.maxCoeff() > 1)
      throw InvalidInputError("painter: background colour must be in [0, 1]");
    map = build_texel_map(m, p, o.width, o.height, true);
    // The spatial index and the seam padding both depend on the texel map only: side by side (each
    // is serial in part; 1024² Painter setup, bench_paint).
    tbb::parallel_invoke([&] { build_index(); },
                         [&] { padding = build_seam_padding(map, o.padding); });
    reset_colours();
  }

  /// A copy of \p o on equal copies \p m, \p p of its mesh and parameterization (no open stroke).
  Impl(const Impl &o, const TriMesh &m, const Parameterization &p)
      : mesh(m), param(p), options(o.options), background(o.background), map(o.map),
        grid(std::make_unique<detail::TexelGrid>(*o.grid)), padding(o.padding), slot_ij(o.slot_ij),
        slot_texel(o.slot_texel), texel_slot(o.texel_slot), point_slot(o.point_slot), colour(o.colour), base(o.base), alpha(o.alpha),
        tex(o.tex), dirty(o.dirty), painted(o.painted), updates(o.updates) {}

  /// The texel points' spatial index and the slot <-> texel tables. Slots are the texels in the
  /// index's order; a shared texel's other points (aliases) map to its slot through point_slot.
  void build_index() {
    const size_t n = map.inside.size();
    std::vector<Vec3f> pts(n + map.aliases.size());
    for (size_t k = 0; k < n; ++k)
      pts[k] = map.position[map.inside[k]];
    for (size_t a = 0; a < map.aliases.size(); ++a)
      pts[n + a] = map.aliases[a].position;
    const double area = surface_area(mesh);
    const double spacing =
        pts.empty() ? 1.0 : std::sqrt(std::max(area, 1e-300) / n);
    grid = std::make_unique<detail::TexelGrid>(pts, spacing);
    slot_ij.resize(n);
    slot_texel.resize(n);
    texel_slot.assign(map.face.size(), -1);
    const int W = options.width;
    size_t s = 0;
    for (size_t g = 0; g < pts.size(); ++g) {
      const int k = grid->order()[g];
      if (static_cast<size_t>(k) >= n)
        continue;
      const int t = map.inside[k];
      slot_texel[s] = t;
      slot_ij[s] = static_cast<std::uint32_t>(t % W) |
                   static_cast<std::uint32_t>(t / W) << 16;
      texel_slot[t] = static_cast<int>(s++);
    }
    point_slot.clear();
    if (map.aliases.empty())
      return;
    point_slot.resize(pts.size());
    for (size_t g = 0; g < pts.size(); ++g) {
      const size_t k = static_cast<size_t>(grid->order()[g]);
      point_slot[g] = texel_slot[k < n ? map.inside[k] : map.aliases[k - n].texel];
    }
  }

  /// Calls fn(slot, squared distance) for every texel point within \p r of \p c (a shared texel
  /// once per point of it that is).
  template <class Fn> void for_each_in_ball(const Vec3 &c, double r, Fn &&fn) const {
    if (point_slot.empty())
      return grid->for_each_in_ball(c, r, fn);
    grid->for_each_in_ball(c, r, [&](int g, float d2) { fn(point_slot[static_cast<size_t>(g)], d2); });
  }

  void reset_colours() {
    const std::array<float, 3> bg{float(background[0]), float(background[1]),
                                  float(background[2])};
    colour.assign(slot_texel.size(), bg);
    base.assign(slot_texel.size(), bg);
    alpha.assign(slot_texel.size(), 0.0f);
    tex = ImageRGBA8(options.width, options.height,
                     {to8(bg[0]), to8(bg[1]), to8(bg[2]), 0});
    dirty = Rect{};
    dirty.add(0, 0);
    dirty.add(options.width - 1, options.height - 1);
  }

  void set_style(const Stroke &s) {
    validate_stroke(s, "painter");
    for (int c = 0; c < 3; ++c)
      col[c] = static_cast<float>(s.color[c]);
    radius = static_cast<float>(s.radius);
    hardness = static_cast<float>(s.hardness);
    opacity = static_cast<float>(s.opacity);
  }

  /// Sequential dab: updates colour at once (interactive).
  Rect dab(const Vec3 &c) {
    Rect rect;
    const float inv_r = 1.0f / radius;
    long long n = 0;
    for_each_in_ball(c, radius, [&](int s, float d2) {
      ++n;
      const float w = opacity * falloff_f(std::sqrt(d2) * inv_r, hardness);
      float &a = alpha[s];
      if (!(w > a))
        return;
      if (a == 0.0f) {
        base[s] = colour[s];
        touched.push_back(s);
      }
      a = w;
      const auto &b = base[s];
      auto &out = colour[s];
      for (int k = 0; k < 3; ++k)
        out[k] = b[k] * (1.0f - w) + col[k] * w;
      rect.add(static_cast<int>(slot_ij[s] & 0xffff),
               static_cast<int>(slot_ij[s] >> 16));
    });
    updates += n;
    dirty.add(rect);
    painted = true;
    return rect;
  }

  void close() {
    for (int s : touched)
      alpha[s] = 0.0f;
    touched.clear();
    open = false;
  }

  /// Whole brush stroke, dabs in parallel: max coverage with atomics, then one
  /// composite pass.
  void parallel_stroke(const Stroke &s) {
    tbb::enumerable_thread_specific<std::vector<int>> first_touch;
    tbb::combinable<long long> count([] { return 0LL; });
    const float inv_r = 1.0f / radius;
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, s.dabs.size(), 8),
        [&](const tbb::blocked_range<size_t> &r) {
          auto &mine = first_touch.local();
          long long n = 0;
          for (size_t d = r.begin(); d < r.end(); ++d)
            for_each_in_ball(s.dabs[d], radius, [&](int slot, float d2) {
              ++n;
              const float w =
                  opacity * falloff_f(std::sqrt(d2) * inv_r, hardness);
              std::atomic_ref<float> a(alpha[slot]);
              float cur = a.load(std::memory_order_relaxed);
              while (w > cur) {
                if (a.compare_exchange_weak(cur, w,
                                            std::memory_order_relaxed)) {
                  if (cur == 0.0f)
                    mine.push_back(slot);
                  break;
                }
              }
            });
          count.local() += n;
        });
    updates += count.combine(std::plus<long long>());
    tbb::combinable<Rect> rects;
    for (auto &list : first_touch) {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, list.size(), 1024),
                        [&](const tbb::blocked_range<size_t> &r) {
                          Rect &rect = rects.local();
                          for (size_t k = r.begin(); k < r.end(); ++k) {
                            const int slot = list[k];
                            const float w = alpha[slot];
                            auto &out = colour[slot];
                            const auto b = out;
                            for (int c = 0; c < 3; ++c)
                              out[c] = b[c] * (1.0f - w) + col[c] * w;
                            alpha[slot] = 0.0f;
                            rect.add(static_cast<int>(slot_ij[slot] & 0xffff),
                                     static_cast<int>(slot_ij[slot] >> 16));
                          }
                        });
    }
    rects.combine_each([&](const Rect &r) { dirty.add(r); });
    painted = true;
  }

  void decal_stroke(const Stroke &s) {
    validate_stroke(s, "painter");
    if (!projector)
      projector = std::make_unique<DecalProjector>(mesh);
    tbb::combinable<Rect> rects;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, slot_texel.size(), 256),
                      [&](const tbb::blocked_range<size_t> &r) {
                        Rect &rect = rects.local();
                        for (size_t slot = r.begin(); slot < r.end(); ++slot) {
                          const int t = slot_texel[slot];
                          const Eigen::Vector4d v = projector->evaluate(
                              s, map.position[t].cast<double>(), map.face[t]);
                          const float a = static_cast<float>(v[3]);
                          if (!(a > 0))
                            continue;
                          auto &out = colour[slot];
                          for (int c = 0; c < 3; ++c)
                            out[c] = out[c] * (1.0f - a) +
                                     static_cast<float>(v[c]) * a;
                          rect.add(static_cast<int>(slot_ij[slot] & 0xffff),
                                   static_cast<int>(slot_ij[slot] >> 16));
                        }
                      });
    rects.combine_each([&](const Rect &r) { dirty.add(r); });
    updates += static_cast<long long>(slot_texel.size());
    painted = true;
  }

  void refresh() {
    if (dirty.empty())
      return;
    const int W = options.width, H = options.height, P = options.padding;
    const Rect r = dirty;
    dirty = Rect{};
    tbb::parallel_for(tbb::blocked_range<int>(r.j0, r.j1 + 1, 16),
                      [&](const tbb::blocked_range<int> &rows) {
                        for (int j = rows.begin(); j < rows.end(); ++j)
                          for (int i = r.i0; i <= r.i1; ++i) {
                            const int t = j * W + i;
                            if (map.face[t] < 0)
                              continue;
                            const int s = texel_slot[t];
                            std::uint8_t *px =
                                &tex.data[static_cast<size_t>(t) * 4];
                            px[0] = to8(colour[s][0]);
                            px[1] = to8(colour[s][1]);
                            px[2] = to8(colour[s][2]);
                            px[3] = 255;
                          }
                      });
    if (P == 0)
      return;
    const int i0 = std::max(0, r.i0 - P), i1 = std::min(W - 1, r.i1 + P);
    const int j0 = std::max(0, r.j0 - P), j1 = std::min(H - 1, r.j1 + P);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const int t = j * W + i;
        const int src = padding.source[t];
        if (src < 0)
          continue;
        for (int c = 0; c < 4; ++c)
          tex.data[static_cast<size_t>(t) * 4 + c] =
              tex.data[static_cast<size_t>(src) * 4 + c];
      }
  }
};

Painter::Painter(const TriMesh &mesh, const Parameterization &param,
                 const PainterOptions &options, const Vec3 &background)
    : impl_(std::make_unique<Impl>(mesh, param, options, background)) {}
Painter::Painter(const Painter &other, const TriMesh &mesh, const Parameterization &param) {
  const Impl &o = *other.impl_;
  if (o.open)
    throw Error("painter: copied while a stroke is open");
  const bool same_mesh = &mesh == &o.mesh || (mesh.faces == o.mesh.faces && mesh.positions == o.mesh.positions);
  const bool same_param = &param == &o.param || (param.uv == o.param.uv && param.uv_faces == o.param.uv_faces);
  if (!same_mesh || !same_param)
    throw InvalidInputError("painter: a copy needs the same mesh and parameterization as the original");
  impl_ = std::make_unique<Impl>(o, mesh, param);
}
Painter::~Painter() = default;
Painter::Painter(Painter &&) noexcept = default;
Painter &Painter::operator=(Painter &&) noexcept = default;

void Painter::paint_stroke(const Stroke &stroke) {
  Impl &m = *impl_;
  if (m.open)
    throw Error(
        "painter: paint_stroke() called while an interactive stroke is open");
  if (stroke.type == Stroke::Type::Decal) {
    m.decal_stroke(stroke);
    return;
  }
  m.set_style(stroke);
  if (stroke.dabs.size() >= 16 && tbb::this_task_arena::max_concurrency() > 1) {
    m.parallel_stroke(stroke);
    return;
  }
  for (const Vec3 &c : stroke.dabs)
    m.dab(c);
  m.close();
}

void Painter::paint_all(const StrokeFile &file) {
  Impl &m = *impl_;
  if (!m.painted && file.background != m.background) {
    m.background = file.background;
    m.reset_colours();
  }
  for (size_t k = 0; k < file.strokes.size(); ++k)
    paint_stroke(file.strokes[k]);
}

void Painter::begin_stroke(const Stroke &style) {
  Impl &m = *impl_;
  if (m.open)
    throw Error("painter: begin_stroke() called while a stroke is open");
  if (style.type != Stroke::Type::Brush)
    throw InvalidInputError(
        "painter: interactive strokes must be brush strokes");
  Stroke s = style;
  if (s.dabs.empty())
    s.dabs.push_back(Vec3::Zero()); // the style's dabs are ignored
  m.set_style(s);
  m.open = true;
}

std::array<int, 4> Painter::add_dab(const Vec3 &centre) {
  Impl &m = *impl_;
  if (!m.open)
    throw Error("painter: add_dab() called without begin_stroke()");
  if (!centre.allFinite())
    throw InvalidInputError("painter: dab centre is not finite");
  const Rect r = m.dab(centre);
  if (r.empty())
    return {0, 0, -1, -1};
  const int P =
      m.options.padding; // padded texels around the touched ones change too
  return {std::max(0, r.i0 - P), std::max(0, r.j0 - P),
          std::min(m.options.width - 1, r.i1 + P),
          std::min(m.options.height - 1, r.j1 + P)};
}

void Painter::end_stroke() {
  Impl &m = *impl_;
  if (!m.open)
    throw Error("painter: end_stroke() called without begin_stroke()");
  m.close();
}

void Painter::fill_colours(const std::vector<Vec3f> &colours) {
  Impl &m = *impl_;
  if (m.open)
    throw Error("painter: fill_colours() called while a stroke is open");
  if (colours.size() != m.map.inside.size())
    throw InvalidInputError("painter: fill_colours() needs " + std::to_string(m.map.inside.size()) +
                            " colours, got " + std::to_string(colours.size()));
  if (!std::all_of(colours.begin(), colours.end(), [](const Vec3f &c) { return c.allFinite(); }))
    throw InvalidInputError("painter: fill_colours() got a colour that is not finite");
  tbb::parallel_for(size_t(0), colours.size(), [&](size_t k) {
    const int s = m.texel_slot[m.map.inside[k]];
    for (int c = 0; c < 3; ++c)
      m.colour[s][c] = std::clamp(colours[k][c], 0.0f, 1.0f);
  });
  m.dirty.add(0, 0);
  m.dirty.add(m.options.width - 1, m.options.height - 1);
  m.painted = true;
}

std::vector<Vec3f> Painter::colours() const {
  const Impl &m = *impl_;
  if (m.open)
    throw Error("painter: colours() called while a stroke is open");
  std::vector<Vec3f> out(m.map.inside.size());
  tbb::parallel_for(size_t(0), out.size(), [&](size_t k) {
    const auto &c = m.colour[m.texel_slot[m.map.inside[k]]];
    out[k] = Vec3f(c[0], c[1], c[2]);
  });
  return out;
}

const ImageRGBA8 &Painter::texture() {
  impl_->refresh();
  return impl_->tex;
}

const TexelMap &Painter::texel_map() const { return impl_->map; }

long long Painter::texel_updates() const { return impl_->updates; }

} // namespace adaptex
