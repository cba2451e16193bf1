// density-flow on multi-chart layouts: charts re-packed by their density share, one flow per chart
// rectangle (atlas_flow.h).
#include "adaptex/adapt/atlas_flow.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "adaptex/core/errors.h"
#include "adaptex/param/pack.h"

namespace adaptex {

std::vector<UvRect> chart_boxes(const Parameterization& param) {
  const int C = param.num_charts;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<UvRect> boxes(C, UvRect{Vec2(inf, inf), Vec2(-inf, -inf)});
  for (size_t f = 0; f < param.uv_faces.size(); ++f) {
    UvRect& b = boxes[param.face_chart[f]];
    for (int w : param.uv_faces[f]) {
      b.lo = b.lo.cwiseMin(param.uv[w]);
      b.hi = b.hi.cwiseMax(param.uv[w]);
    }
  }
  for (UvRect& b : boxes)
    if (!(b.lo.x() <= b.hi.x())) b = UvRect{};
  return boxes;
}

double smallest_box_gap(const std::vector<UvRect>& boxes) {
  double gap = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < boxes.size(); ++i) {
    const UvRect& a = boxes[i];
    for (size_t j = i + 1; j < boxes.size(); ++j) {
      const UvRect& b = boxes[j];
      // Separation along the axis that separates them most (negative: they overlap on both axes).
      const double dx = std::max(b.lo.x() - a.hi.x(), a.lo.x() - b.hi.x());
      const double dy = std::max(b.lo.y() - a.hi.y(), a.lo.y() - b.hi.y());
      gap = std::min(gap, std::max(dx, dy));
    }
  }
  return gap;
}

namespace {
/// bilinear_tap() at the k sample positions lo + (i + 0.5) / k · size along one axis of \p n texels.
std::vector<BilinearTap> axis_taps(int n, int k, double lo, double size) {
  std::vector<BilinearTap> t(static_cast<size_t>(k));
  for (int i = 0; i < k; ++i) t[static_cast<size_t>(i)] = bilinear_tap(n, lo + (i + 0.5) / k * size);
  return t;
}

/// Mean of \p density over \p r, sampled on a regular grid of about samples_per_cell points per
/// density cell and axis (the values sample_bilinear() gives there, summed in raster order).
double mean_density(const ImageF& density, const UvRect& r, int samples_per_cell) {
  const int L = density.width;
  const int kx = std::clamp(static_cast<int>(std::ceil(r.size().x() * L * samples_per_cell)), 2, 4 * L);
  const int ky = std::clamp(static_cast<int>(std::ceil(r.size().y() * L * samples_per_cell)), 2, 4 * L);
  const std::vector<BilinearTap> tx = axis_taps(density.width, kx, r.lo.x(), r.size().x()),
                                 ty = axis_taps(density.height, ky, r.lo.y(), r.size().y());
  double sum = 0;
  for (const BilinearTap& y : ty) {
    const float* row0 = density.data.data() + static_cast<size_t>(y.i0) * density.width;
    const float* row1 = density.data.data() + static_cast<size_t>(y.i1) * density.width;
    for (const BilinearTap& x : tx) {  // sample_bilinear()'s arithmetic
      const double a = row0[x.i0], b = row0[x.i1], d = row1[x.i0], e = row1[x.i1];
      const double bottom = a + (b - a) * x.f, top = d + (e - d) * x.f;
      sum += bottom + (top - bottom) * y.f;
    }
  }
  return sum / (double(kx) * ky);
}

void check_density(const ImageF& density, const char* who) {
  if (density.width < 1 || density.height < 1 || density.data.empty())
    throw InvalidInputError(std::string(who) + ": empty density raster");
}

void check_repack(const std::vector<UvRect>& boxes, const ImageF& density, const ChartRepackOptions& o) {
  check_density(density, "repack_charts_by_density");
  if (!(o.padding >= 0 && o.padding < 0.25)) throw InvalidInputError("repack_charts_by_density: padding must be in [0, 0.25)");
  if (o.samples_per_cell < 1) throw InvalidInputError("repack_charts_by_density: samples_per_cell must be >= 1");
  if (boxes.empty()) throw InvalidInputError("repack_charts_by_density: no charts");
}

/// Mean density over every chart's box (0 for empty boxes).
std::vector<double> chart_means(const std::vector<UvRect>& boxes, const ImageF& density, const ChartRepackOptions& o) {
  std::vector<double> m(boxes.size(), 0.0);
  for (size_t c = 0; c < boxes.size(); ++c)
    if (boxes[c].area() > 0) m[c] = std::max(mean_density(density, boxes[c], o.samples_per_cell), 1e-12);
  return m;
}

/// The charts packed with sizes ∝ mean^(γ/2) × their boxes.
std::vector<ChartMove> repack_with(const std::vector<UvRect>& boxes, const std::vector<double>& mean, double gamma,
                                   const ChartRepackOptions& o) {
  // The texel budget of a chart is ∫ρ over its rectangle; at γ = 1 its new area is proportional to
  // that, so its linear scale is proportional to sqrt(mean ρ) (pack_rectangles scales all together).
  std::vector<Vec2> sizes(boxes.size(), Vec2::Zero());
  for (size_t c = 0; c < boxes.size(); ++c) {
    if (boxes[c].area() <= 0) continue;  // an unused chart id or a degenerate chart: smallest size
    sizes[c] = (gamma == 1.0 ? std::sqrt(mean[c]) : std::pow(mean[c], 0.5 * gamma)) * boxes[c].size();
  }
  const std::vector<RectPlacement> placed = pack_rectangles(sizes, o.padding);
  std::vector<ChartMove> moves(boxes.size());
  for (size_t c = 0; c < boxes.size(); ++c) {
    moves[c].src = boxes[c];
    moves[c].dst_lo = placed[c].offset;
    const Vec2 s = boxes[c].size();
    // pack_rectangles keeps each rectangle's aspect; take the scale of its longer side (exact for
    // that side; the other matches up to round-off) and never exceed the placed rectangle.
    moves[c].scale = s.maxCoeff() > 0 ? std::min(s.x() > 0 ? placed[c].size.x() / s.x() : 1e300,
                                                  s.y() > 0 ? placed[c].size.y() / s.y() : 1e300)
                                      : 1.0;
  }
  return moves;
}

/// The error model's terms of the cells that some chart's box covers, in raster order (a later box
/// wins where boxes share a cell): a candidate re-packing only changes each chart's scale, so
/// predicted_error() needs one exp per term, not a raster pass with a pow per cell.
struct ErrorTerms {
  struct Term {
    int chart;
    double q, half_p, log_rho;  // error, p/2, log of the density
  };
  std::vector<Term> terms;

  ErrorTerms(const std::vector<UvRect>& boxes, const ImageF& density, const ImageF& error, const ImageF& exponent) {
    const int L = density.width;
    std::vector<int> owner(static_cast<size_t>(L) * L, -1);
    for (size_t c = 0; c < boxes.size(); ++c) {
      const UvRect& b = boxes[c];
      if (b.area() <= 0) continue;
      const int i0 = std::max(0, static_cast<int>(std::ceil(b.lo.x() * L - 0.5)));
      const int i1 = std::min(L - 1, static_cast<int>(std::floor(b.hi.x() * L - 0.5)));
      const int j0 = std::max(0, static_cast<int>(std::ceil(b.lo.y() * L - 0.5)));
      const int j1 = std::min(L - 1, static_cast<int>(std::floor(b.hi.y() * L - 0.5)));
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) owner[static_cast<size_t>(j) * L + i] = static_cast<int>(c);
    }
    for (size_t k = 0; k < owner.size(); ++k) {
      const double q = error.data[k];
      if (owner[k] < 0 || !(q > 0)) continue;
      terms.push_back(Term{owner[k], q, 0.5 * exponent.data[k], std::log(static_cast<double>(density.data[k]))});
    }
  }

  /// Σ q (s² ρ / mean)^(−p/2) over the terms, s = moves[chart].scale, ρ·s²/mean clamped at 1e-12.
  double predicted_error(const std::vector<ChartMove>& moves, const std::vector<double>& mean) const {
    std::vector<double> log_gain(moves.size());
    for (size_t c = 0; c < moves.size(); ++c)
      log_gain[c] = mean[c] > 0 ? std::log(moves[c].scale * moves[c].scale / mean[c]) : 0.0;
    const double log_min = std::log(1e-12);
    double e = 0;
    for (const Term& t : terms)
      e += t.q * std::exp(-t.half_p * std::max(log_gain[static_cast<size_t>(t.chart)] + t.log_rho, log_min));
    return e;
  }
};

}  // namespace

std::vector<ChartMove> repack_charts_by_density(const std::vector<UvRect>& boxes, const ImageF& density,
                                                const ChartRepackOptions& o) {
  check_repack(boxes, density, o);
  return repack_with(boxes, chart_means(boxes, density, o), 1.0, o);
}

namespace {
void check_error_rasters(const ImageF& density, const ImageF& error, const ImageF& exponent, const char* who) {
  check_density(density, who);
  if (density.width != density.height || error.width != density.width || error.height != density.height ||
      exponent.width != density.width || exponent.height != density.height)
    throw InvalidInputError(std::string(who) + ": the density, error and exponent rasters must be the same square size");
}
}  // namespace

double predicted_chart_error(const std::vector<ChartMove>& moves, const ImageF& density, const ImageF& error,
                             const ImageF& exponent, const ChartRepackOptions& o) {
  check_error_rasters(density, error, exponent, "predicted_chart_error");
  std::vector<UvRect> boxes(moves.size());
  for (size_t c = 0; c < moves.size(); ++c) boxes[c] = moves[c].src;
  return ErrorTerms(boxes, density, error, exponent).predicted_error(moves, chart_means(boxes, density, o));
}

std::vector<ChartMove> allocate_charts_by_error(const std::vector<UvRect>& boxes, const ImageF& density,
                                                const ImageF& error, const ImageF& exponent,
                                                const ChartRepackOptions& o, double* chosen_gamma) {
  check_repack(boxes, density, o);
  check_error_rasters(density, error, exponent, "allocate_charts_by_error");
  const std::vector<double> mean = chart_means(boxes, density, o);
  const ErrorTerms terms(boxes, density, error, exponent);
  std::vector<ChartMove> best;
  double best_e = std::numeric_limits<double>::infinity(), best_g = 1.0;
  for (double gamma : {1.0, 0.75, 0.5, 0.25, 0.0}) {
    std::vector<ChartMove> m = repack_with(boxes, mean, gamma, o);
    const double e = terms.predicted_error(m, mean);
    if (e < best_e) best_e = e, best = std::move(m), best_g = gamma;
  }
  // Leaving the charts in place is a candidate only where it keeps the promise of every re-packing:
  // rectangles at least the padding apart and from the square's sides.
  bool stay_ok = smallest_box_gap(boxes) >= o.padding;
  for (const UvRect& b : boxes)
    if (b.area() > 0 && (b.lo.minCoeff() < o.padding || b.hi.maxCoeff() > 1 - o.padding)) stay_ok = false;
  if (stay_ok) {
    std::vector<ChartMove> stay(boxes.size());
    for (size_t c = 0; c < boxes.size(); ++c) stay[c].src = boxes[c], stay[c].dst_lo = boxes[c].lo;
    if (terms.predicted_error(stay, mean) < best_e) best = std::move(stay), best_g = -1.0;
  }
  if (chosen_gamma) *chosen_gamma = best_g;
  return best;
}

Parameterization move_charts(const Parameterization& param, const std::vector<ChartMove>& moves) {
  if (static_cast<int>(moves.size()) != param.num_charts)
    throw InvalidInputError("move_charts: " + std::to_string(moves.size()) + " moves for " +
                            std::to_string(param.num_charts) + " charts");
  Parameterization out = param;
  std::vector<char> done(param.uv.size(), 0);
  for (size_t f = 0; f < param.uv_faces.size(); ++f)
    for (int w : param.uv_faces[f])
      if (!done[w]) {
        done[w] = 1;
        const Vec2 p = moves[param.face_chart[f]].apply(param.uv[w]);
        out.uv[w] = p.cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1));
      }
  return out;
}

ChartMoveLocator::ChartMoveLocator(std::vector<ChartMove> moves) : moves_(std::move(moves)) {
  n_ = std::clamp(static_cast<int>(std::sqrt(double(moves_.size()))) * 2, 1, 256);
  buckets_.resize(static_cast<size_t>(n_) * n_);
  auto cell = [this](double x) { return std::clamp(static_cast<int>(x * n_), 0, n_ - 1); };
  for (size_t c = 0; c < moves_.size(); ++c) {
    const UvRect& r = moves_[c].src;
    if (r.area() <= 0 && r.size().maxCoeff() <= 0) continue;
    for (int y = cell(r.lo.y()); y <= cell(r.hi.y()); ++y)
      for (int x = cell(r.lo.x()); x <= cell(r.hi.x()); ++x) buckets_[static_cast<size_t>(y) * n_ + x].push_back(static_cast<int>(c));
  }
}

Vec2 ChartMoveLocator::apply(const Vec2& uv) const {
  auto cell = [this](double x) { return std::clamp(static_cast<int>(x * n_), 0, n_ - 1); };
  constexpr double eps = 1e-12;
  for (int c : buckets_[static_cast<size_t>(cell(uv.y())) * n_ + cell(uv.x())]) {
    const ChartMove& m = moves_[c];
    if (uv.x() >= m.src.lo.x() - eps && uv.x() <= m.src.hi.x() + eps && uv.y() >= m.src.lo.y() - eps &&
        uv.y() <= m.src.hi.y() + eps)
      return m.apply(uv).cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1));
  }
  return uv;
}

std::vector<int> chart_lattice_cells(const std::vector<ChartMove>& moves, int cells, int min_cells) {
  if (cells < 1 || min_cells < 1) throw InvalidInputError("chart_lattice_cells: cells must be >= 1");
  const int lo = std::min(min_cells, cells);
  // As fine as one lattice of `cells` over the square, at the chart's larger size (old or new).
  std::vector<double> side(moves.size());
  double points = 0;
  for (size_t c = 0; c < moves.size(); ++c) {
    side[c] = std::max(moves[c].dst().size().maxCoeff(), moves[c].src.size().maxCoeff()) * cells;
    points += (side[c] + 1) * (side[c] + 1);
  }
  // Elongated boxes (the lattice is square) and the larger of the two sizes can add up to several
  // square lattices: scale down to one.
  const double budget = double(cells + 1) * (cells + 1);
  const double scale = points > budget ? std::sqrt(budget / points) : 1.0;
  std::vector<int> n(moves.size());
  for (size_t c = 0; c < moves.size(); ++c) {
    const double want = side[c] * scale;
    // From 16 cells on, the nearest multiple of 4: the flow then builds the lattice coarse to fine
    // over at least two levels and interpolates where the map is smooth (density_flow.h,
    // interpolation_tolerance); an odd lattice advects every point.
    const int k = want >= 16 ? 4 * static_cast<int>(std::lround(want / 4)) : static_cast<int>(std::ceil(want));
    n[c] = std::clamp(k, lo, cells);
  }
  return n;
}

namespace {
/// \p density over the chart's src rectangle, resampled on an n x n raster (2 x 2 samples per cell),
/// floored at 1e-9 (the flow needs ρ > 0).
ImageF local_density(const ImageF& density, const UvRect& src, int n) {
  ImageF local(n, n, 0.0f);
  constexpr int sub = 2;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double sum = 0;
      for (int b = 0; b < sub; ++b)
        for (int a = 0; a < sub; ++a) {
          const double u = (i + (a + 0.5) / sub) / n, v = (j + (b + 0.5) / sub) / n;
          sum += sample_bilinear(density, src.lo.x() + u * src.size().x(), src.lo.y() + v * src.size().y());
        }
      local.at(i, j) = static_cast<float>(std::max(sum / (sub * sub), 1e-9));
    }
  return local;
}
}  // namespace

std::vector<GridWarp> chart_flow_warps(const std::vector<ChartMove>& moves, const ImageF& density,
                                       const DensityFlowOptions& flow, int min_cells, DensityFlowStats* stats) {
  check_density(density, "chart_flow_warps");
  if (flow.cells < 1 || min_cells < 1) throw InvalidInputError("chart_flow_warps: cells must be >= 1");
  const int C = static_cast<int>(moves.size());
  std::vector<GridWarp> warps(C);
  std::vector<DensityFlowStats> st(C);
  const std::vector<int> cells = chart_lattice_cells(moves, flow.cells, min_cells);
  tbb::parallel_for(0, C, [&](int c) {
    const ChartMove& m = moves[c];
    const UvRect dst = m.dst();
    if (m.src.size().minCoeff() <= 0) {  // degenerate chart (no area): the identity
      warps[c] = GridWarp::uniform(1);
      return;
    }
    const int n = cells[c];
    const ImageF local = local_density(density, m.src, n);
    DensityFlowOptions fo = flow;
    fo.cells = n;
    warps[c] = density_equalizing_warp(local, fo, &st[c]);
    warps[c].lo = dst.lo;
    warps[c].hi = dst.hi;
  });
  if (stats) {
    *stats = DensityFlowStats{};
    for (const DensityFlowStats& s : st) {
      stats->total_steps += s.total_steps;
      stats->advected_points += s.advected_points;
      stats->max_steps = std::max(stats->max_steps, s.max_steps);
      stats->max_displacement = std::max(stats->max_displacement, s.max_displacement);
      stats->tangled_cells += s.tangled_cells;
      stats->inverted_cells += s.inverted_cells;
      stats->density_error += s.density_error / std::max(1, C);
    }
  }
  return warps;
}

FlowWarp chart_flows(const std::vector<ChartMove>& moves, const ImageF& density, const DensityFlowOptions& flow,
                     int min_cells) {
  check_density(density, "chart_flows");
  if (min_cells < 2) throw InvalidInputError("chart_flows: min_cells must be >= 2");
  const int C = static_cast<int>(moves.size());
  FlowWarp fw;
  fw.options = flow;
  fw.parts.resize(C);
  const int L = std::max(density.width, density.height);
  tbb::parallel_for(0, C, [&](int c) {
    const ChartMove& m = moves[c];
    const UvRect dst = m.dst();
    fw.parts[c].lo = dst.lo;
    fw.parts[c].hi = dst.hi;
    if (m.src.size().minCoeff() <= 0) return;  // degenerate chart (no area): the identity
    // The density raster's own resolution over the chart's rectangle (its longer side): the flow's
    // cost is its DCT and the points advected, not its raster.
    const int n = std::clamp(static_cast<int>(std::ceil(m.src.size().maxCoeff() * L)), min_cells, 2 * L);
    fw.parts[c].flow = std::make_shared<const DensityFlow>(local_density(density, m.src, n));
  });
  return fw;
}

}  // namespace adaptex
