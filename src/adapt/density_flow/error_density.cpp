// Error-model target density (error_density.h; derivation in docs/error_model.md).
#include "adaptex/adapt/error_density.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/errors.h"
#include "adaptex/paint/material_paint.h"  // texel_points()
#include "adaptex/paint/signal.h"

namespace adaptex {

namespace {

/// An RGB raster over [0,1]² (texel centres at (i+0.5)/size), values everywhere (padded outside charts).
struct Raster {
  int size = 0;
  std::vector<Vec3f> rgb;  // size², row-major, row 0 at v = 0

  Vec3f sample(double u, double v) const {  // bilinear, clamp-to-edge (the contract's reconstruction)
    const double x = std::clamp(u * size - 0.5, 0.0, size - 1.0), y = std::clamp(v * size - 0.5, 0.0, size - 1.0);
    const int i = std::min(static_cast<int>(x), size - 2 < 0 ? 0 : size - 2);
    const int j = std::min(static_cast<int>(y), size - 2 < 0 ? 0 : size - 2);
    const int i1 = std::min(i + 1, size - 1), j1 = std::min(j + 1, size - 1);
    const float s = static_cast<float>(x - i), t = static_cast<float>(y - j);
    const auto at = [&](int a, int b) { return rgb[static_cast<size_t>(b) * size + a]; };
    return (1 - t) * ((1 - s) * at(i, j) + s * at(i1, j)) + t * ((1 - s) * at(i, j1) + s * at(i1, j1));
  }
};

/// The texture as a raster (square textures as they are; others resampled bilinearly to max(W, H)²),
/// into \p r (its storage reused).
void from_texture(const ImageRGBA8& tex, Raster& r) {
  r.size = std::max(tex.width, tex.height);
  r.rgb.resize(static_cast<size_t>(r.size) * r.size);
  if (tex.width == tex.height) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, r.rgb.size(), 1 << 15), [&](const tbb::blocked_range<size_t>& b) {
      for (size_t k = b.begin(); k < b.end(); ++k)
        r.rgb[k] = Vec3f(tex.data[4 * k], tex.data[4 * k + 1], tex.data[4 * k + 2]) / 255.0f;
    });
    return;
  }
  for (int j = 0; j < r.size; ++j)
    for (int i = 0; i < r.size; ++i)
      r.rgb[static_cast<size_t>(j) * r.size + i] = sample_bilinear(tex, (i + 0.5) / r.size, (j + 0.5) / r.size).cast<float>();
}

Raster from_texture(const ImageRGBA8& tex) {
  Raster r;
  from_texture(tex, r);
  return r;
}

/// Point samples of \p src (bilinear) at the texel centres of a size² raster: what a texture of that
/// size would hold if it were made from \p src.
Raster resampled(const Raster& src, int size) {
  Raster r;
  r.size = size;
  r.rgb.resize(static_cast<size_t>(size) * size);
  tbb::parallel_for(0, size, [&](int j) {
    for (int i = 0; i < size; ++i) r.rgb[static_cast<size_t>(j) * size + i] = src.sample((i + 0.5) / size, (j + 0.5) / size);
  });
  return r;
}

/// Outside-chart texels take the mean of their already-filled neighbours, ring after ring (like the
/// seam padding of a painted texture), so bilinear taps at chart borders see chart colours.
/// A ring reads only texels filled before it and writes only texels that were not: rows in parallel.
void pad_outside(Raster& r, std::vector<char> filled, int rings) {
  const int n = r.size;
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> next = filled;
    tbb::parallel_for(0, n, [&](int j) {
      for (int i = 0; i < n; ++i) {
        const size_t k = static_cast<size_t>(j) * n + i;
        if (filled[k]) continue;
        Vec3f sum = Vec3f::Zero();
        int cnt = 0;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int a = i + di, b = j + dj;
            if (a < 0 || b < 0 || a >= n || b >= n) continue;
            const size_t q = static_cast<size_t>(b) * n + a;
            if (filled[q]) sum += r.rgb[q], ++cnt;
          }
        if (cnt) r.rgb[k] = sum / static_cast<float>(cnt), next[k] = 1;
      }
    });
    if (next == filled) break;  // nothing was filled: the later rings would change nothing either
    filled.swap(next);
  }
}

/// The raster of \p map holding \p c (the signal at texel_points(map)) inside charts, padded outside
/// if \p pad (see exact_raster()).
Raster signal_raster(const TexelMap& map, const std::vector<Vec3>& c, const Vec3& background, bool pad) {
  Raster r;
  r.size = map.width;
  r.rgb.assign(static_cast<size_t>(map.width) * map.height, background.cast<float>());
  std::vector<char> filled(r.rgb.size(), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, c.size(), 1 << 15), [&](const tbb::blocked_range<size_t>& b) {
    for (size_t k = b.begin(); k < b.end(); ++k) r.rgb[map.inside[k]] = c[k].cast<float>(), filled[map.inside[k]] = 1;
  });
  if (pad) pad_outside(r, std::move(filled), 4);
  return r;
}

/// A conservative test of "no brush dab of the history reaches the 3-D point p": a uniform grid over
/// the dabs' balls (cells of the smallest radius, at most kCells along the longest side), a cell marked
/// where the bounding box of some dab's ball meets it. Where may_reach() is false StrokeSignal gives
/// exactly the background (no dab within its radius: no hit), so the error model evaluates the history
/// only near the paint (venus, `lines` at 256²: 11.4k of the 262k 2N reference texels differ from the
/// background, 17.6k are evaluated). Every point may be reached when the history has decals, or when
/// marking would take more than \p budget rows of cells.
class DabReach {
 public:
  /// \param slack grows every ball (world units): a bound on how far the points given to may_reach()
  ///        may lie from the points StrokeSignal is evaluated at (texel_map's float positions)
  DabReach(const StrokeFile& history, double budget, double slack) {
    Eigen::AlignedBox3d box;
    double r_min = std::numeric_limits<double>::infinity();
    for (const Stroke& st : history.strokes) {
      if (st.type == Stroke::Type::Decal) return;  // all_ stays true
      for (const Vec3& c : st.dabs) box.extend(c - Vec3::Constant(st.radius)), box.extend(c + Vec3::Constant(st.radius));
      if (!st.dabs.empty()) r_min = std::min(r_min, st.radius);
    }
    all_ = false;
    if (box.isEmpty()) return;  // no dab at all: nothing is reached
    const double extent = box.sizes().maxCoeff();
    cell_ = std::max({extent / kCells, r_min, 1e-300});
    inv_cell_ = 1.0 / cell_;
    grow_ = slack + 1e-6 * cell_;  // and a rounding margin
    origin_ = box.min() - Vec3::Constant(cell_);
    for (int a = 0; a < 3; ++a) dim_[a] = static_cast<int>(std::ceil(box.sizes()[a] / cell_)) + 3;
    // Cost of marking: the rows of cells of every dab's bounding box.
    double visits = 0;
    for (const Stroke& st : history.strokes) visits += st.dabs.size() * std::pow(2 * st.radius / cell_ + 2, 2);  // rows of cells
    if (visits > budget) {
      all_ = true;
      return;
    }
    mark_.assign(static_cast<size_t>(dim_[0]) * dim_[1] * dim_[2], 0);
    for (const Stroke& st : history.strokes)
      for (const Vec3& c : st.dabs) mark_ball(c, st.radius);
  }

  bool may_reach(const Vec3f& p) const {
    if (all_) return true;
    if (mark_.empty()) return false;
    int q[3];
    for (int a = 0; a < 3; ++a) {
      const double f = (p[a] - origin_[a]) * inv_cell_;
      if (!(f >= 0 && f < dim_[a])) return false;  // outside the grid: farther than any radius from every dab
      q[a] = static_cast<int>(f);                  // = floor(f), f >= 0
    }
    return mark_[index(q[0], q[1], q[2])];
  }

 private:
  static constexpr double kCells = 128;  // cells along the longest side of the dabs' box (at most): ≤ 2.2 MB
  bool all_ = true;
  double cell_ = 1, inv_cell_ = 1;
  double grow_ = 0;  // added to every radius when marking
  Vec3 origin_ = Vec3::Zero();
  int dim_[3] = {0, 0, 0};
  std::vector<char> mark_;

  size_t index(int x, int y, int z) const { return (static_cast<size_t>(z) * dim_[1] + y) * dim_[0] + x; }

  /// Marks every cell that meets the bounding box of the ball (\p c, \p radius + grow_) (a row of cells
  /// at a time: no per-cell test).
  void mark_ball(const Vec3& c, double radius) {
    const double r = radius + grow_;
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::clamp(static_cast<int>(std::floor((c[k] - r - origin_[k]) / cell_)), 0, dim_[k] - 1);
      hi[k] = std::clamp(static_cast<int>(std::floor((c[k] + r - origin_[k]) / cell_)), 0, dim_[k] - 1);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y) std::fill_n(mark_.begin() + index(lo[0], y, z), hi[0] - lo[0] + 1, char(1));
  }
};

/// How far a texel map's float position can lie from the point StrokeSignal is evaluated at
/// (point_on_face with the map's float barycentrics): both round at 2^-24 relative, once for the
/// coordinates and once per barycentric times an edge; 1e-6 of the size bounds it with a wide margin.
double position_slack(const TriMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Vec3& p : mesh.positions) box.extend(p);
  if (box.isEmpty()) return 0;
  return 1e-6 * (box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).maxCoeff() + box.diagonal().norm());
}

/// The exact signal at the texel centres of \p map (inside charts), padded outside if \p pad (only
/// rasters read by bilinear lookup need it; the reference is read at chart texels only): evaluated where
/// \p reach says a dab may reach the texel's point, the background elsewhere (what StrokeSignal gives
/// there). Equal to signal_raster(map, signal.evaluate(texel_points(map)), background).
Raster exact_raster(const TriMesh& mesh, const TexelMap& map, const StrokeSignal& signal, const DabReach& reach,
                    const Vec3& background, bool pad) {
  Raster r;
  r.size = map.width;
  r.rgb.assign(static_cast<size_t>(map.width) * map.height, background.cast<float>());
  std::vector<char> filled(r.rgb.size(), 0);
  tbb::parallel_for(0, map.height, [&](int j) {
    for (int i = 0; i < map.width; ++i) {
      const size_t t = static_cast<size_t>(map.index(i, j));
      const int f = map.face[t];
      if (f < 0) continue;
      filled[t] = 1;
      if (reach.may_reach(map.position[t]))
        r.rgb[t] = signal.evaluate(point_on_face(mesh, f, map.bary[t].x(), map.bary[t].y()), f).cast<float>();
    }
  });
  if (pad) pad_outside(r, std::move(filled), 4);
  return r;
}

/// The reference points of a texture of side N: the texel centres of a side² raster moved by −shift
/// in u and v, i.e. at ((i + 0.5)/side − shift, (j + 0.5)/side − shift).
struct ReferenceGrid {
  int side = 0;
  double shift = 0;
  bool operator==(const ReferenceGrid& g) const { return side == g.side && shift == g.shift; }
};

/// ErrorDensityOptions::quarter_texel_reference where N >= 4·cells, else the reference_factor·N
/// raster (capped at max_reference, never coarser than the texture).
ReferenceGrid reference_grid(int n, const ErrorDensityOptions& o) {
  if (o.quarter_texel_reference && n >= 4 * o.cells) return {n, 0.25 / n};
  return {std::max(n, std::min(o.reference_factor * n, o.max_reference)), 0.0};
}

/// The texel map of the reference points: the texel map of \p param shifted by +shift (its texel
/// centre (i + 0.5)/side is the layout's point (i + 0.5)/side − shift).
TexelMap reference_texel_map(const TriMesh& mesh, const Parameterization& param, const ReferenceGrid& g) {
  if (g.shift == 0) return build_texel_map(mesh, param, g.side, g.side);
  Parameterization shifted = param;
  for (Vec2& t : shifted.uv) t += Vec2(g.shift, g.shift);
  return build_texel_map(mesh, shifted, g.side, g.side);
}

/// Surface area per UV area of every face, relative to the whole layout's (1 = average).
std::vector<double> surface_per_uv(const TriMesh& mesh, const Parameterization& param) {
  std::vector<double> ratio(mesh.faces.size(), 0.0);
  double a3 = 0, a2 = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const double s = face_area(mesh, f), u = std::abs(uv_signed_area(param, f));
    a3 += s, a2 += u;
    ratio[f] = u > 0 ? s / u : 0.0;
  }
  const double mean = a2 > 0 ? a3 / a2 : 1.0;
  for (double& r : ratio) r = mean > 0 ? r / mean : 0.0;
  return ratio;
}

/// Per-cell accumulations over the reference raster.
struct CellErrors {
  int n = 0;
  std::vector<double> ea, eb;   // surface-weighted squared error at the two level spacings
  std::vector<double> surface;  // surface measure (Σ relative surface-per-uv of the cell's texels)
  std::vector<double> cover;    // fraction of the cell inside charts
};

/// Raster::sample's taps and weights along one axis, for the reference points (k + 0.5) / R − shift,
/// k < R: a bilinear lookup there is then two table reads per axis (the same arithmetic as sample()).
struct Taps {
  std::vector<int> lo, hi;
  std::vector<float> w;  // weight of hi

  Taps(int size, int R, double shift) : lo(R), hi(R), w(R) {
    for (int k = 0; k < R; ++k) {
      const double x = std::clamp(((k + 0.5) / R - shift) * size - 0.5, 0.0, size - 1.0);
      lo[k] = std::min(static_cast<int>(x), size - 2 < 0 ? 0 : size - 2);
      hi[k] = std::min(lo[k] + 1, size - 1);
      w[k] = static_cast<float>(x - lo[k]);
    }
  }
};

/// \p r bilinearly at the reference point (i, j): Raster::sample((i+0.5)/R − shift, (j+0.5)/R − shift).
inline Vec3f sample_at(const Raster& r, const Taps& x, const Taps& y, int i, int j) {
  const float s = x.w[i], t = y.w[j];
  const Vec3f* row0 = r.rgb.data() + static_cast<size_t>(y.lo[j]) * r.size;
  const Vec3f* row1 = r.rgb.data() + static_cast<size_t>(y.hi[j]) * r.size;
  return (1 - t) * ((1 - s) * row0[x.lo[i]] + s * row0[x.hi[i]]) + t * ((1 - s) * row1[x.lo[i]] + s * row1[x.hi[i]]);
}

/// The reference rows [first, second) whose points lie in cell row \p cj of \p n (R reference rows,
/// shifted by g.shift): row j's points lie at v = (j + 0.5)/R − shift, in cell row floor(v·n).
std::pair<int, int> band_rows(int cj, int n, int R, const ReferenceGrid& g) {
  const double lift = g.shift * R - 0.5;
  const int j0 = cj == 0 ? 0 : static_cast<int>(std::ceil(double(cj) * R / n + lift));
  const int j1 = cj == n - 1 ? R : static_cast<int>(std::ceil(double(cj + 1) * R / n + lift));
  return {std::max(j0, 0), std::min(j1, R)};
}

/// \p ref holds the exact signal at the reference points of \p g (ref_map: their texel map).
/// With \p previous and \p dirty (one flag per cell row): the rows not flagged are copied from
/// \p previous, which must be this function's result for inputs that differ only in flagged rows.
CellErrors accumulate(const Raster& ref, const TexelMap& ref_map, const ReferenceGrid& g, const Raster& a, const Raster& b,
                      const std::vector<double>& ratio, int n, const CellErrors* previous = nullptr,
                      const std::vector<char>* dirty = nullptr) {
  CellErrors c;
  c.n = n;
  const size_t cells = static_cast<size_t>(n) * n;
  c.ea.assign(cells, 0), c.eb.assign(cells, 0), c.surface.assign(cells, 0), c.cover.assign(cells, 0);
  const int R = ref.size;
  const double per_cell = double(R) * R / cells;  // reference texels per cell
  const Taps ax(a.size, R, g.shift), bx(b.size, R, g.shift);  // the same tables serve rows and columns
  // Row bands of cells are independent: parallel over cell rows.
  tbb::parallel_for(0, n, [&](int cj) {
    if (previous && !(*dirty)[static_cast<size_t>(cj)]) {
      const size_t from = static_cast<size_t>(cj) * n, to = from + static_cast<size_t>(n);
      for (auto [dst, src] : {std::pair{&c.ea, &previous->ea}, std::pair{&c.eb, &previous->eb},
                              std::pair{&c.surface, &previous->surface}, std::pair{&c.cover, &previous->cover}})
        std::copy(src->begin() + from, src->begin() + to, dst->begin() + from);
      return;
    }
    const auto [j0, j1] = band_rows(cj, n, R, g);
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < R; ++i) {
        const size_t t = static_cast<size_t>(j) * R + i;
        const int f = ref_map.face[t];
        if (f < 0) continue;
        const double u = (i + 0.5) / R - g.shift;
        const int ci = std::clamp(static_cast<int>(u * n), 0, n - 1);
        const size_t cell = static_cast<size_t>(cj) * n + ci;
        const double w = ratio[f];
        c.ea[cell] += w * (ref.rgb[t] - sample_at(a, ax, ax, i, j)).squaredNorm() / 3.0;
        c.eb[cell] += w * (ref.rgb[t] - sample_at(b, bx, bx, i, j)).squaredNorm() / 3.0;
        c.surface[cell] += w;
        c.cover[cell] = std::min(1.0, c.cover[cell] + 1.0 / per_cell);
      }
  });
  return c;
}

/// One flag per row of \p now: whether it differs from the same row of \p before (bit for bit).
/// \pre equal sizes
std::vector<char> changed_rows(const Raster& now, const Raster& before) {
  const int n = now.size;
  std::vector<char> out(static_cast<size_t>(n), 0);
  tbb::parallel_for(0, n, [&](int j) {
    const size_t k = static_cast<size_t>(j) * n;
    out[static_cast<size_t>(j)] = std::memcmp(now.rgb.data() + k, before.rgb.data() + k, sizeof(Vec3f) * n) != 0;
  });
  return out;
}

/// The cell rows of accumulate() whose inputs differ between (ref, a, b) and (ref0, a0, b0): a row
/// reads its own reference rows and the rows of a and b that their bilinear taps reach.
/// \pre each raster has the size of its counterpart
std::vector<char> dirty_cell_rows(const ReferenceGrid& g, int n, const Raster& ref, const Raster& a, const Raster& b,
                                  const Raster& ref0, const Raster& a0, const Raster& b0) {
  const std::vector<char> dr = changed_rows(ref, ref0), da = changed_rows(a, a0), db = changed_rows(b, b0);
  const int R = ref.size;
  const Taps ax(a.size, R, g.shift), bx(b.size, R, g.shift);
  std::vector<char> out(static_cast<size_t>(n), 0);
  for (int cj = 0; cj < n; ++cj) {
    const auto [j0, j1] = band_rows(cj, n, R, g);
    bool d = false;
    for (int j = j0; j < j1 && !d; ++j)
      d = dr[static_cast<size_t>(j)] || da[static_cast<size_t>(ax.lo[j])] || da[static_cast<size_t>(ax.hi[j])] ||
          db[static_cast<size_t>(bx.lo[j])] || db[static_cast<size_t>(bx.hi[j])];
    out[static_cast<size_t>(cj)] = d;
  }
  return out;
}

/// Equidistribution (see the header): densities per cell with Σ ρ = n², by bisection on log μ.
ErrorDensity solve_density(CellErrors& c, double spacing_ratio, const ErrorDensityOptions& o) {
  const int n = c.n;
  const size_t cells = static_cast<size_t>(n) * n;
  gaussian_blur(c.ea, n, o.blur_cells);
  gaussian_blur(c.eb, n, o.blur_cells);
  ErrorDensity out;
  out.density = ImageF(n, n, 1.0f);
  out.error = ImageF(n, n, 0.0f);
  out.exponent = ImageF(n, n, 0.0f);
  double total_surface = 0, total_cover = 0, max_e = 0;
  for (size_t k = 0; k < cells; ++k) total_surface += c.surface[k], total_cover += c.cover[k], max_e = std::max(max_e, c.ea[k]);
  const double budget = total_cover;  // the chart part of the square, in cells
  std::vector<double> q(cells, 0), p(cells, 0), lo(cells, 0);
  const double noise = 1e-9 * max_e + 1e-30;
  int with_signal = 0, chart_cells = 0;
  for (size_t k = 0; k < cells; ++k) {
    if (c.cover[k] <= 0) continue;
    ++chart_cells;
    // Least density: floor × the uniform-surface-density share of this cell.
    lo[k] = total_surface > 0 ? o.floor * budget * c.surface[k] / total_surface / c.cover[k] : o.floor;
    lo[k] = std::clamp(lo[k], 1e-6, o.max_density);
    if (c.ea[k] <= noise) continue;
    ++with_signal;
    p[k] = std::clamp(std::log2(std::max(c.eb[k], c.ea[k]) / c.ea[k]), o.min_exponent, o.max_exponent);
    q[k] = spacing_ratio == 1.0 ? c.ea[k] : c.ea[k] * std::pow(spacing_ratio, p[k]);  // error at the spacing h_N
  }
  out.signal_fraction = chart_cells ? double(with_signal) / chart_cells : 0.0;
  // ρ = clamp(exp(e·(log(p q / 2) − log μ)), lo, max) with e = 1 / (1 + p/2): the exponent and the
  // log are per cell, computed once; the bisection then costs one exp per painted cell per step.
  std::vector<double> ek(cells, 0.0), ak(cells, 0.0);
  std::vector<size_t> painted;
  double unpainted = 0;  // Σ cover·lo over chart cells without signal (independent of μ)
  for (size_t k = 0; k < cells; ++k) {
    if (c.cover[k] <= 0) continue;
    if (q[k] <= 0) {
      unpainted += c.cover[k] * lo[k];
      continue;
    }
    ek[k] = 1.0 / (1.0 + 0.5 * p[k]);
    ak[k] = std::log(0.5 * p[k] * q[k]);
    painted.push_back(k);
  }
  auto rho_of = [&](size_t k, double log_mu) {
    if (q[k] <= 0) return lo[k];
    return std::clamp(std::exp(ek[k] * (ak[k] - log_mu)), lo[k], o.max_density);
  };
  // total(log μ) and its derivative: d ρ / d log μ = −e·ρ where ρ is not clamped.
  auto total = [&](double log_mu, double* slope) {
    double s = unpainted, d = 0;
    for (size_t k : painted) {
      const double r = std::exp(ek[k] * (ak[k] - log_mu));
      if (r <= lo[k]) s += c.cover[k] * lo[k];
      else if (r >= o.max_density) s += c.cover[k] * o.max_density;
      else s += c.cover[k] * r, d -= c.cover[k] * ek[k] * r;
    }
    if (slope) *slope = d;
    return s;
  };
  // Safeguarded Newton on the decreasing function total(log μ) − budget inside a bisection bracket:
  // about 10 evaluations where plain bisection down to adjacent doubles took about 60 (one exp per
  // painted cell each; measured: the larger part of solve_density's time).
  double a = -200, b = 200;  // log μ bracket: total(a) is large, total(b) small
  double x = 0.5 * (a + b);
  for (int it = 0; it < 200; ++it) {
    double slope = 0;
    const double f = total(x, &slope) - budget;
    if (std::abs(f) <= 1e-12 * budget) break;
    (f > 0 ? a : b) = x;
    const double newton = slope < 0 ? x - f / slope : std::numeric_limits<double>::quiet_NaN();
    const double next = newton > a && newton < b ? newton : 0.5 * (a + b);
    if (next <= a || next >= b || next == x) break;  // the bracket is down to adjacent doubles
    x = next;
  }
  const double log_mu = x;
  // Gutters between charts take the density of the charts around them (a cover-weighted blur), so the
  // flow is as smooth across a gutter as inside a chart; a fixed gutter density (ρ = 1) next to
  // compressed unpainted charts made steep density steps at every chart border, and the sheared
  // borders flipped or crossed (measured on the 32-chart spot layout).
  std::vector<double> rho(cells, 0.0), rc(cells, 0.0), wc(cells, 0.0);
  for (size_t k = 0; k < cells; ++k)
    if (c.cover[k] > 0) rho[k] = rho_of(k, log_mu), rc[k] = c.cover[k] * rho[k], wc[k] = c.cover[k];
  gaussian_blur(rc, n, o.gutter_blur_cells);
  gaussian_blur(wc, n, o.gutter_blur_cells);
  double before = 0, after = 0, sum = 0;
  for (size_t k = 0; k < cells; ++k) {
    const double gutter = wc[k] > 1e-6 ? rc[k] / wc[k] : 1.0;
    const double r = c.cover[k] > 0 ? c.cover[k] * rho[k] + (1 - c.cover[k]) * gutter : gutter;
    out.density.data[k] = static_cast<float>(r);
    sum += r;
    out.error.data[k] = static_cast<float>(q[k]);
    out.exponent.data[k] = static_cast<float>(p[k]);
    if (q[k] > 0) before += q[k], after += q[k] * std::pow(rho[k], -0.5 * p[k]);
  }
  for (float& v : out.density.data) v = static_cast<float>(v * cells / sum);  // mean exactly 1
  out.predicted_gain_db = before > 0 && after > 0 ? 10 * std::log10(before / after) : 0.0;
  return out;
}

void check(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& tex, const TexelMap& map,
           const ErrorDensityOptions& o, bool square) {
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("error density: parameterization and mesh have different face counts");
  if (tex.empty() || (square && tex.width != tex.height))
    throw InvalidInputError(square ? "error density: the texture must be square and non-empty"
                                   : "error density: empty texture");
  if (map.width != tex.width || map.height != tex.height)
    throw InvalidInputError("error density: texel map size differs from the texture size");
  if (o.cells < 2 || o.cells > 4096) throw InvalidInputError("error density: cells must be in [2, 4096]");
  if (o.reference_factor < 1 || o.max_reference < 1) throw InvalidInputError("error density: bad reference size");
  if (!(o.floor > 0 && o.floor <= 1)) throw InvalidInputError("error density: floor must be in (0, 1]");
  if (!(o.max_density >= 1) || !(o.min_exponent > 0) || !(o.max_exponent >= o.min_exponent) || !(o.blur_cells >= 0))
    throw InvalidInputError("error density: bad max_density / exponent range / blur");
}

/// The density from the reference raster \p ref (texel map \p ref_map) and the N/2 level \p level_b of
/// the exact signal; level a is the texture itself (what the painter stored at h_N).
ErrorDensity from_levels(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                         const Raster& ref, const TexelMap& ref_map, const ReferenceGrid& g, const Raster& level_b,
                         const ErrorDensityOptions& o) {
  const Raster level_a = from_texture(texture);
  // The density raster is never finer than the reference raster (every cell holds reference texels).
  CellErrors c = accumulate(ref, ref_map, g, level_a, level_b, surface_per_uv(mesh, param), std::min(o.cells, ref.size));
  ErrorDensity out = solve_density(c, 1.0, o);
  out.reference_size = ref.size;
  return out;
}
}  // namespace

ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                                   const TexelMap& map, const StrokeFile& history, const ErrorDensityOptions& o) {
  check(mesh, param, texture, map, o, true);
  const int N = texture.width;
  const ReferenceGrid g = reference_grid(N, o);
  const int R = g.side;
  const StrokeSignal signal(mesh, history);
  const TexelMap ref_map = reference_texel_map(mesh, param, g);
  // Marking may fill up to two rows of cells per reference texel (far less than evaluating them).
  const DabReach reach(history, 2.0 * R * R, position_slack(mesh));
  const Raster ref = exact_raster(mesh, ref_map, signal, reach, history.background, false);
  const int half = std::max(1, N / 2);
  const Raster level_b = exact_raster(mesh, build_texel_map(mesh, param, half, half), signal, reach, history.background, true);
  return from_levels(mesh, param, texture, ref, ref_map, g, level_b, o);
}

namespace {

/// The raster of \p map holding \p values inside charts, padded outside if \p pad, into \p r (its
/// storage reused).
void plane_raster(const TexelMap& map, const std::vector<Vec3f>& values, bool pad, Raster& r) {
  r.size = map.width;
  r.rgb.assign(static_cast<size_t>(map.width) * map.height, Vec3f::Zero());
  for (int t : map.inside) r.rgb[t] = values[t];
  if (!pad) return;
  std::vector<char> filled(r.rgb.size(), 0);
  for (int t : map.inside) filled[t] = 1;
  pad_outside(r, std::move(filled), 4);
}

}  // namespace

ErrorPlaneMaps error_plane_maps(const TriMesh& mesh, const Parameterization& param, int texture_size,
                                const ErrorDensityOptions& o) {
  if (texture_size < 1) throw InvalidInputError("error density: texture size < 1");
  if (o.reference_factor < 1 || o.max_reference < 1) throw InvalidInputError("error density: bad reference size");
  const int half = std::max(1, texture_size / 2);
  return ErrorPlaneMaps{texture_size, reference_texel_map(mesh, param, reference_grid(texture_size, o)),
                        build_texel_map(mesh, param, half, half)};
}

ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                   const std::vector<ErrorPlane>& planes, const ErrorDensityOptions& o) {
  if (planes.empty()) throw InvalidInputError("error density: no plane");
  return compute_error_density(mesh, param, map, planes, error_plane_maps(mesh, param, map.width, o), o);
}

ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                   const std::vector<ErrorPlane>& planes, const ErrorPlaneMaps& maps,
                                   const ErrorDensityOptions& o) {
  ErrorPlanesMemory none;
  return compute_error_density(mesh, param, map, planes, maps, none, o);
}

/// The last call's rasters and cell sums of each plane (empty: none yet).
struct ErrorPlanesMemory::Impl {
  struct Plane {
    Raster ref, a, b;
    CellErrors cells;
  };
  const ErrorPlaneMaps* maps = nullptr;
  int cells = 0;
  ReferenceGrid grid;
  std::vector<double> ratio;  // surface_per_uv of the layout
  std::vector<Plane> planes;
  std::vector<Plane> spare;   // the call before last's: storage for the next call's rasters
};

ErrorPlanesMemory::ErrorPlanesMemory() : impl_(std::make_unique<Impl>()) {}
ErrorPlanesMemory::~ErrorPlanesMemory() = default;
ErrorPlanesMemory::ErrorPlanesMemory(ErrorPlanesMemory&&) noexcept = default;
ErrorPlanesMemory& ErrorPlanesMemory::operator=(ErrorPlanesMemory&&) noexcept = default;

ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                   const std::vector<ErrorPlane>& planes, const ErrorPlaneMaps& maps,
                                   ErrorPlanesMemory& memory, const ErrorDensityOptions& o) {
  if (planes.empty()) throw InvalidInputError("error density: no plane");
  for (const ErrorPlane& p : planes) {
    if (!(p.weight > 0) || !std::isfinite(p.weight)) throw InvalidInputError("error density: a plane weight is not > 0");
    if (!p.exact) throw InvalidInputError("error density: a plane has no exact signal");
    check(mesh, param, p.texture, map, o, true);
  }
  const int N = map.width;
  const ReferenceGrid g = reference_grid(N, o);
  if (maps.texture_size != N || maps.reference.width != g.side || maps.half.width != std::max(1, N / 2))
    throw InvalidInputError("error density: the plane maps are of another texture size or reference grid");
  const TexelMap& ref_map = maps.reference;
  const TexelMap& half_map = maps.half;
  const int cells = std::min(o.cells, g.side);
  ErrorPlanesMemory::Impl& m = *memory.impl_;
  if (m.maps != &maps || m.cells != cells || !(m.grid == g) || m.planes.size() != planes.size()) {
    m = ErrorPlanesMemory::Impl{};
    m.maps = &maps, m.cells = cells, m.grid = g;
    m.ratio = surface_per_uv(mesh, param);
    m.planes.resize(planes.size());
    m.spare.resize(planes.size());
  }
  CellErrors sum;
  for (size_t k = 0; k < planes.size(); ++k) {
    const ErrorPlane& p = planes[k];
    ErrorPlanesMemory::Impl::Plane& now = m.spare[k];
    plane_raster(ref_map, p.exact(ref_map), false, now.ref);
    plane_raster(half_map, p.exact(half_map), true, now.b);
    from_texture(p.texture, now.a);
    // As accumulate() afresh, summing again only the cell rows whose inputs changed since the last call.
    const ErrorPlanesMemory::Impl::Plane& prev = m.planes[k];
    const bool again = prev.cells.n == cells && prev.ref.size == now.ref.size && prev.a.size == now.a.size &&
                       prev.b.size == now.b.size;
    const std::vector<char> dirty =
        again ? dirty_cell_rows(g, cells, now.ref, now.a, now.b, prev.ref, prev.a, prev.b) : std::vector<char>{};
    now.cells = accumulate(now.ref, ref_map, g, now.a, now.b, m.ratio, cells, again ? &prev.cells : nullptr,
                           again ? &dirty : nullptr);
    const CellErrors& c = now.cells;
    if (k == 0) {
      sum = c;
      for (size_t i = 0; i < sum.ea.size(); ++i) sum.ea[i] *= p.weight, sum.eb[i] *= p.weight;
    } else {
      for (size_t i = 0; i < sum.ea.size(); ++i) sum.ea[i] += p.weight * c.ea[i], sum.eb[i] += p.weight * c.eb[i];
    }
    std::swap(m.planes[k], now);
  }
  ErrorDensity out = solve_density(sum, 1.0, o);
  out.reference_size = g.side;
  return out;
}

struct ErrorDensityReference::Impl {
  const TriMesh* mesh = nullptr;
  std::vector<Vec2> uv;              // the layout it was built for
  std::vector<Face> uv_faces;
  int texture_size = 0;
  ReferenceGrid grid;
  TexelMap ref_map, half_map;
  PointSignalCache ref_signal, half_signal;
  // The last compute_error_density() with this reference: its three rasters and cell sums. The next
  // call (after a stroke) sums again only the cell rows whose rasters changed (after a stroke,
  // only the dirty region's density inputs change). Empty before the first call.
  struct Last {
    Raster ref, a, b;
    CellErrors cells;
  };
  std::unique_ptr<Last> last;
  std::vector<double> ratio;  // surface_per_uv of the layout, computed at the first call
};

ErrorDensityReference::ErrorDensityReference(const TriMesh& mesh, const Parameterization& param, int texture_size,
                                             const Vec3& background, const ErrorDensityOptions& o) {
  if (param.uv_faces.size() != mesh.faces.size() || texture_size < 1)
    throw InvalidInputError("error density reference: layout and mesh differ, or texture size < 1");
  if (o.reference_factor < 1 || o.max_reference < 1) throw InvalidInputError("error density: bad reference size");
  const ReferenceGrid g = reference_grid(texture_size, o);
  const int half = std::max(1, texture_size / 2);
  TexelMap ref_map = reference_texel_map(mesh, param, g);
  TexelMap half_map = build_texel_map(mesh, param, half, half);
  PointSignalCache ref_signal(mesh, texel_points(ref_map), background);
  PointSignalCache half_signal(mesh, texel_points(half_map), background);
  impl_ = std::make_unique<Impl>(Impl{&mesh, param.uv, param.uv_faces, texture_size, g,
                                      std::move(ref_map), std::move(half_map), std::move(ref_signal),
                                      std::move(half_signal), nullptr, {}});
}

ErrorDensityReference::~ErrorDensityReference() = default;
ErrorDensityReference::ErrorDensityReference(ErrorDensityReference&&) noexcept = default;
ErrorDensityReference& ErrorDensityReference::operator=(ErrorDensityReference&&) noexcept = default;

bool ErrorDensityReference::matches(const TriMesh& mesh, const Parameterization& param, int texture_size,
                                    const ErrorDensityOptions& o) const {
  return &mesh == impl_->mesh && texture_size == impl_->texture_size && reference_grid(texture_size, o) == impl_->grid &&
         param.uv == impl_->uv && param.uv_faces == impl_->uv_faces;
}

void ErrorDensityReference::update(const StrokeFile& history) {
  impl_->ref_signal.update(history);
  impl_->half_signal.update(history);
}

ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                                   const TexelMap& map, const StrokeFile& history, ErrorDensityReference& reference,
                                   const ErrorDensityOptions& o) {
  check(mesh, param, texture, map, o, true);
  if (!reference.matches(mesh, param, texture.width, o))
    throw InvalidInputError("error density: the reference was built for another layout or texture size");
  reference.update(history);
  ErrorDensityReference::Impl& r = *reference.impl_;
  auto last = std::make_unique<ErrorDensityReference::Impl::Last>();
  last->ref = signal_raster(r.ref_map, r.ref_signal.values(), history.background, false);
  last->b = signal_raster(r.half_map, r.half_signal.values(), history.background, true);
  last->a = from_texture(texture);
  if (r.ratio.empty()) r.ratio = surface_per_uv(mesh, param);
  // As from_levels(), summing again only the cell rows whose inputs changed since the last call.
  const int n = std::min(o.cells, last->ref.size);
  const ErrorDensityReference::Impl::Last* prev = r.last.get();
  if (prev && !(prev->cells.n == n && prev->ref.size == last->ref.size && prev->a.size == last->a.size &&
                prev->b.size == last->b.size))
    prev = nullptr;
  const std::vector<char> dirty =
      prev ? dirty_cell_rows(r.grid, n, last->ref, last->a, last->b, prev->ref, prev->a, prev->b) : std::vector<char>{};
  last->cells = accumulate(last->ref, r.ref_map, r.grid, last->a, last->b, r.ratio, n, prev ? &prev->cells : nullptr,
                           prev ? &dirty : nullptr);
  CellErrors c = last->cells;  // solve_density blurs its input
  ErrorDensity out = solve_density(c, 1.0, o);
  out.reference_size = last->ref.size;
  r.last = std::move(last);
  return out;
}

double predicted_error(const ErrorDensity& model, const ImageF& density) {
  const ImageF& q = model.error;
  const ImageF& p = model.exponent;
  if (p.width != q.width || p.height != q.height)
    throw InvalidInputError("predicted_error: the model's error and exponent rasters differ in size");
  const bool uniform = density.data.empty();
  if (!uniform && (density.width != q.width || density.height != q.height))
    throw InvalidInputError("predicted_error: density is " + std::to_string(density.width) + " x " +
                            std::to_string(density.height) + ", the model " + std::to_string(q.width) + " x " +
                            std::to_string(q.height));
  double e = 0;
  for (size_t k = 0; k < q.data.size(); ++k) {
    if (!(q.data[k] > 0)) continue;
    const double rho = uniform ? 1.0 : density.data[k];
    if (!(rho > 0) || !std::isfinite(rho)) throw InvalidInputError("predicted_error: density is not finite and > 0");
    e += q.data[k] * std::pow(rho, -0.5 * p.data[k]);
  }
  return e;
}

ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                                   const TexelMap& map, const ErrorDensityOptions& o) {
  check(mesh, param, texture, map, o, false);
  const Raster ref = from_texture(texture);
  const int N = ref.size;
  const TexelMap square_map = texture.width == texture.height ? TexelMap{} : build_texel_map(mesh, param, N, N);
  const Raster level_a = resampled(ref, std::max(1, N / 2));
  const Raster level_b = resampled(ref, std::max(1, N / 4));
  CellErrors c = accumulate(ref, texture.width == texture.height ? map : square_map, ReferenceGrid{N, 0.0}, level_a, level_b,
                            surface_per_uv(mesh, param), std::min(o.cells, N));
  // Level a has spacing 2·h_N: the error at h_N extrapolates by 2^(−p).
  ErrorDensity out = solve_density(c, 0.5, o);
  out.reference_size = N;
  return out;
}

}  // namespace adaptex
