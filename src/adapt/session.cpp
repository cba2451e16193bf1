// PaintSession: the painting loop with signal-adaptive re-parameterization (thesis Fig. 3.1).
#include "adaptex/adapt/session.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/blocked_range.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "adaptex/adapt/stretch_map.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/timer.h"
#include "adaptex/io/image_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/padding.h"
#include "adaptex/paint/signal.h"

namespace adaptex {

namespace {
double reconstruction_mse(const Parameterization& param, const ImageRGBA8& tex, const std::vector<SurfacePoint>& pts,
                          const std::vector<Vec3>& exact) {
  if (pts.empty()) return 0;
  const double sum = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, pts.size(), 1024), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double s) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
          const Face& w = param.uv_faces[pts[k].face];
          const double b2 = 1 - pts[k].b0 - pts[k].b1;
          const Vec2 uv = pts[k].b0 * param.uv[w[0]] + pts[k].b1 * param.uv[w[1]] + b2 * param.uv[w[2]];
          s += (sample_bilinear(tex, uv.x(), uv.y()) - exact[k]).squaredNorm();
        }
        return s;
      },
      std::plus<double>());
  return sum / (3.0 * pts.size());
}

/// The surface points \p pts of mesh \p from moved to a refinement \p to of it (parent_face[c] = face of
/// \p from that child c lies on): the same 3-D points, on the child face that contains them.
std::vector<SurfacePoint> transfer_points(const std::vector<SurfacePoint>& pts, const TriMesh& from, const TriMesh& to,
                                          const FaceData<int>& parent_face) {
  std::vector<int> start(from.faces.size() + 1, 0), children(parent_face.size());
  for (int p : parent_face) ++start[p + 1];
  for (size_t f = 0; f < from.faces.size(); ++f) start[f + 1] += start[f];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (size_t c = 0; c < parent_face.size(); ++c) children[fill[parent_face[c]]++] = static_cast<int>(c);
  std::vector<SurfacePoint> out(pts.size());
  tbb::parallel_for(size_t(0), pts.size(), [&](size_t k) {
    const Vec3 p = point_on_face(from, pts[k].face, pts[k].b0, pts[k].b1);
    double best = -std::numeric_limits<double>::infinity();
    bool found = false;
    for (int q = start[pts[k].face]; q < start[pts[k].face + 1]; ++q) {
      const int c = children[q];
      const Face& f = to.faces[c];
      const Vec3 e1 = to.positions[f[1]] - to.positions[f[0]], e2 = to.positions[f[2]] - to.positions[f[0]];
      const Vec3 d = p - to.positions[f[0]];
      const double a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2), det = a11 * a22 - a12 * a12;
      if (!(det > 0)) continue;
      const double l1 = (a22 * e1.dot(d) - a12 * e2.dot(d)) / det, l2 = (a11 * e2.dot(d) - a12 * e1.dot(d)) / det;
      const double inside = std::min({1 - l1 - l2, l1, l2});
      if (inside > best) {
        best = inside;
        found = true;
        const double c1 = std::clamp(l1, 0.0, 1.0), c2 = std::clamp(l2, 0.0, 1.0 - c1);
        out[k] = SurfacePoint{c, 1 - c1 - c2, c1};
      }
    }
    if (!found)  // only degenerate children: any child's centre (same parent face, same surface)
      out[k] = SurfacePoint{start[pts[k].face] < start[pts[k].face + 1] ? children[start[pts[k].face]] : pts[k].face,
                            1.0 / 3, 1.0 / 3};
  });
  return out;
}

// Strokes painted since the last re-parameterization, in resample mode: composited over the
// resampled base as C = base * T + S, with S the segment painted over black and T + S over white
// (compositing is affine in the colour underneath).
struct Segment {
  Painter black, white;
  bool empty = true;
};
}  // namespace

ReparamSchedule parse_reparam_schedule(const std::string& name) {
  if (name == "each-stroke" || name == "each_stroke") return ReparamSchedule::EachStroke;
  if (name == "end") return ReparamSchedule::End;
  throw InvalidInputError("unknown reparam schedule '" + name + "' (expected each-stroke or end)");
}

TextureUpdate parse_texture_update(const std::string& name) {
  if (name == "replay") return TextureUpdate::Replay;
  if (name == "resample") return TextureUpdate::Resample;
  throw InvalidInputError("unknown texture update '" + name + "' (expected replay or resample)");
}

PaintSessionOptions make_session_options(int size, int padding, const std::string& mode,
                                         const std::vector<int>& grid, double alpha, double beta,
                                         const std::string& reparam, const std::string& update,
                                         const std::filesystem::path& debug_maps) {
  PaintSessionOptions o;
  o.texture_size = size;
  o.padding = padding;
  o.adapt.mode = parse_adapt_mode(mode);
  if (grid.size() > 2) throw InvalidInputError("--grid: give FINE or COARSE,FINE (e.g. 16,256)");
  for (int g : grid)
    if (g < 1 || g > 4096) throw InvalidInputError("--grid: sizes must be in [1, 4096], got " + std::to_string(g));
  if (!grid.empty()) o.adapt.fine_grid = grid.back();
  if (grid.size() == 2) o.adapt.coarse_grid = grid.front();
  if (alpha >= 0) o.adapt.alpha = alpha;
  if (beta >= 0) o.adapt.beta = beta;
  if (!std::isfinite(alpha) || !std::isfinite(beta)) throw InvalidInputError("--alpha/--beta must be finite");
  o.schedule = parse_reparam_schedule(reparam);
  o.update = parse_texture_update(update);
  o.debug_dir = debug_maps;
  return o;
}

struct PaintSession::Impl {
  TriMesh mesh;  // the input mesh
  // The mesh of param when a re-parameterization refined it (same surface, more faces); null: mesh.
  std::shared_ptr<const TriMesh> refined;
  std::vector<SurfacePoint> refined_samples;  // the safeguard samples moved onto *refined
  const TriMesh& current_mesh() const { return refined ? *refined : mesh; }
  const std::vector<SurfacePoint>& current_samples() const { return refined ? refined_samples : samples; }
  PaintSessionOptions opt;
  std::unique_ptr<Parameterization> param;
  std::unique_ptr<Painter> painter;
  // Each-stroke mode: every re-parameterization starts from the initial layout (base) and the history
  // painted on it, so warps never compose over many strokes (no drift, no accumulated distortion) and
  // the last one equals what end mode computes.
  std::unique_ptr<Parameterization> base_param;
  std::unique_ptr<Painter> base_painter;
  StrokeFile history;
  std::vector<AdaptReport> reports;
  std::unique_ptr<AdaptResult> last;
  // Resample mode after the first re-parameterization: base texture + segment painters.
  bool resampled = false;
  ImageRGBA8 base;
  std::unique_ptr<Segment> segment;
  ImageRGBA8 composite;
  bool composite_dirty = true;
  Stroke open_style;
  std::vector<Vec3> open_dabs;
  bool open = false;
  std::vector<SurfacePoint> samples;
  int reparam_count = 0;
  bool adapted = false;  ///< A re-parameterization has been accepted: the current layout is adapted.

  PainterOptions painter_options(const Vec3&) const {
    PainterOptions p;
    p.width = p.height = opt.texture_size;
    p.padding = opt.padding;
    return p;
  }

  const ImageRGBA8& texture() {
    if (!resampled) return painter->texture();
    if (!segment || segment->empty) return base;
    if (composite_dirty) {
      composite = base;
      const ImageRGBA8& b = segment->black.texture();
      const ImageRGBA8& w = segment->white.texture();
      const TexelMap& map = painter->texel_map();
      for (int t : map.inside)
        for (int c = 0; c < 3; ++c) {
          const size_t k = static_cast<size_t>(t) * 4 + c;
          const double S = b.data[k] / 255.0, T = std::max(0.0, w.data[k] / 255.0 - S);
          composite.data[k] = static_cast<std::uint8_t>(std::lround(std::clamp(composite.data[k] / 255.0 * T + S, 0.0, 1.0) * 255));
        }
      apply_seam_padding(composite, build_seam_padding(map, opt.padding));
      composite_dirty = false;
    }
    return composite;
  }

  void new_segment() {
    PainterOptions po = painter_options(history.background);
    segment = std::make_unique<Segment>(Segment{Painter(current_mesh(), *param, po, Vec3(0, 0, 0)),
                                                Painter(current_mesh(), *param, po, Vec3(1, 1, 1)), true});
  }

  void paint(const Stroke& s) {
    if (base_painter) base_painter->paint_stroke(s);
    painter->paint_stroke(s);  // keeps the painter's own (replay-exact) texture for the history too
    if (resampled) {
      segment->black.paint_stroke(s);
      segment->white.paint_stroke(s);
      segment->empty = false;
      composite_dirty = true;
    }
  }

  double estimate(const Parameterization& p, const ImageRGBA8& tex, const std::vector<Vec3>& exact) {
    return reconstruction_mse(p, tex, current_samples(), exact);
  }

  const AdaptReport& reparameterize() {
    const auto t_all = std::chrono::steady_clock::now();
    AdaptOptions ao = opt.adapt;
    if (ao.mode == AdaptMode::None) ao.mode = AdaptOptions{}.mode;  // explicit request: the default method
    // Resample mode maps old texels to new ones face by face: it keeps the mesh.
    if (opt.update == TextureUpdate::Resample) ao.refine = false;
    const ImageRGBA8& tex = texture();
    // Each-stroke mode starts from the initial layout on the input mesh, end mode from the current one.
    const TriMesh& src_mesh = base_param ? mesh : current_mesh();
    const Parameterization& src = base_param ? *base_param : *param;
    auto res = std::make_unique<AdaptResult>(
        base_painter ? adapt_parameterization(mesh, src, base_painter->texture(), base_painter->texel_map(), ao, &history)
                     : adapt_parameterization(src_mesh, src, tex, painter->texel_map(), ao, &history));
    const TriMesh& cand_mesh = res->refined_mesh ? *res->refined_mesh : src_mesh;
    AdaptReport& rep = res->report;
    if (!opt.debug_dir.empty())
      write_debug_maps(opt.debug_dir, "reparam" + std::to_string(reparam_count), *res);
    ++reparam_count;
    if (!rep.accepted || (rep.damping == 0 && res->chart_moves.empty())) {
      rep.time_total = seconds_since(t_all);
      reports.push_back(rep);
      last = std::move(res);
      return reports.back();
    }
    const PainterOptions po = painter_options(history.background);
    const bool use_safeguard = opt.safeguard && !history.strokes.empty();
    auto t0 = std::chrono::steady_clock::now();
    if (use_safeguard && samples.empty()) samples = sample_surface(mesh, opt.safeguard_samples, 0x5eedada);
    if (refined && refined_samples.size() != samples.size()) refined_samples = sample_surface(*refined, opt.safeguard_samples, 0x5eedada);
    // The safeguard's points on the candidate's mesh: the source mesh's points, moved onto the
    // refined mesh when the re-parameterization refined it (the same 3-D points).
    const std::vector<SurfacePoint>& src_pts = base_param ? samples : current_samples();
    std::vector<SurfacePoint> cand_samples;
    if (res->refined_mesh && !src_pts.empty())
      cand_samples = transfer_points(src_pts, src_mesh, cand_mesh, res->parent_face);
    const std::vector<SurfacePoint>& cand_pts = res->refined_mesh ? cand_samples : src_pts;
    std::vector<Vec3> exact;
    if (use_safeguard) {
      exact = StrokeSignal(cand_mesh, history).evaluate(cand_pts);
      // Without refinement the candidate's points are the current ones: evaluate the signal once.
      const bool same_points = &cand_pts == &current_samples();
      rep.error_before = estimate(*param, tex, same_points ? exact : StrokeSignal(current_mesh(), history).evaluate(current_samples()));
    }
    auto estimate_candidate = [&](const Parameterization& p, const ImageRGBA8& t) {
      return reconstruction_mse(p, t, cand_pts, exact);
    };
    rep.time_safeguard += seconds_since(t0);

    // Candidate(s): the full result, then (safeguard only) the result damped by half.
    auto make = [&](double t, std::unique_ptr<Parameterization>& np, std::unique_ptr<Painter>& npainter,
                    ImageRGBA8& ntex) {
      if (t == 1.0) {
        np = std::make_unique<Parameterization>(res->param);
      } else {
        std::vector<GridWarp> half;
        for (const GridWarp* w : res->warps()) half.push_back(w->blended(t * rep.damping));
        std::vector<const GridWarp*> ptrs;
        for (auto& w : half) ptrs.push_back(&w);
        np = std::make_unique<Parameterization>(
            safe_remap(res->start_layout(src), ptrs, ao.remap).param);
      }
      auto tm = std::chrono::steady_clock::now();
      npainter = std::make_unique<Painter>(cand_mesh, *np, po, history.background);
      rep.time_texel_map += seconds_since(tm);
      tm = std::chrono::steady_clock::now();
      if (opt.update == TextureUpdate::Replay) {
        for (const Stroke& s : history.strokes) npainter->paint_stroke(s);
        ntex = npainter->texture();
      } else {
        auto to8 = [](double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
        const Vec3& bg = history.background;
        ntex = resample_texture(*param, tex, npainter->texel_map(), opt.padding,
                                {to8(bg[0]), to8(bg[1]), to8(bg[2]), 0});
        // The visible texture is the resampled one; the new painter only provides the texel map
        // (and the segment painters paint the strokes that follow).
      }
      rep.time_texture_update += seconds_since(tm);
    };
    std::unique_ptr<Parameterization> np;
    std::unique_ptr<Painter> npainter;
    ImageRGBA8 ntex;
    make(1.0, np, npainter, ntex);
    bool accept = true;
    if (use_safeguard) {
      t0 = std::chrono::steady_clock::now();
      rep.error_after = estimate_candidate(*np, ntex);
      // The margin guards the fixed layout against an adapted one that only the estimate finds better.
      // Once the current layout is itself adapted, any better candidate replaces it: each-stroke mode
      // must end on the layout end mode would give (measured: spot lines 256², 50 strokes, the margin
      // kept a layout of an earlier stroke, 0.25 dB below end mode).
      const double limit = rep.error_before * (1.0 - (adapted ? 0.0 : opt.safeguard_margin));
      accept = rep.error_after < limit;
      rep.time_safeguard += seconds_since(t0);
      if (!accept) {
        std::unique_ptr<Parameterization> hp;
        std::unique_ptr<Painter> hpainter;
        ImageRGBA8 htex;
        make(0.5, hp, hpainter, htex);
        t0 = std::chrono::steady_clock::now();
        const double eh = estimate_candidate(*hp, htex);
        rep.time_safeguard += seconds_since(t0);
        if (eh < limit) {
          np = std::move(hp);
          npainter = std::move(hpainter);
          ntex = std::move(htex);
          rep.error_after = eh;
          rep.damping *= 0.5;
          accept = true;
        }
      }
    }
    if (accept) {
      adapted = true;
      res->param = *np;
      painter = std::move(npainter);  // references *np and cand_mesh: keep both alive
      param = std::move(np);
      if (res->refined_mesh) {
        refined_samples = std::move(cand_samples);
        refined = res->refined_mesh;
      } else if (base_param) {
        refined.reset();  // each-stroke: an unrefined candidate lives on the input mesh
        refined_samples.clear();
      }
      if (opt.update == TextureUpdate::Resample) {
        resampled = true;
        base = std::move(ntex);
        new_segment();
        composite_dirty = true;
      }
    } else {
      rep.accepted = false;
      rep.damping = 0;
      rep.l2_after = rep.l2_before;
      rep.faces_after = current_mesh().num_faces();
      res->param = *param;
      res->refined_mesh = refined;
      res->refined_layout.reset();
      res->parent_face.clear();
    }
    rep.time_total = seconds_since(t_all);
    reports.push_back(rep);
    last = std::move(res);
    return reports.back();
  }
};

PaintSession::PaintSession(TriMesh mesh, Parameterization initial, const PaintSessionOptions& options,
                           const Vec3& background)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (initial.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("paint session: parameterization has " + std::to_string(initial.uv_faces.size()) +
                            " faces, mesh has " + std::to_string(mesh.faces.size()));
  if (options.texture_size < 1 || options.texture_size > kMaxTextureSize)
    throw InvalidInputError("paint session: texture size must be in [1, " + std::to_string(kMaxTextureSize) + "], got " +
                            std::to_string(options.texture_size));
  if (options.padding < 0) throw InvalidInputError("paint session: padding must be >= 0");
  if (options.safeguard_samples < 0) throw InvalidInputError("paint session: safeguard_samples must be >= 0");
  m.mesh = std::move(mesh);
  m.opt = options;
  m.history.background = background;
  m.param = std::make_unique<Parameterization>(std::move(initial));
  m.painter = std::make_unique<Painter>(m.mesh, *m.param, m.painter_options(background), background);
  if (options.schedule == ReparamSchedule::EachStroke && options.adapt.mode != AdaptMode::None) {
    m.base_param = std::make_unique<Parameterization>(*m.param);
    m.base_painter = std::make_unique<Painter>(m.mesh, *m.base_param, m.painter_options(background), background);
  }
}

PaintSession::~PaintSession() = default;

void PaintSession::add_stroke(const Stroke& stroke) {
  Impl& m = *impl_;
  if (m.open) throw Error("paint session: add_stroke() while an interactive stroke is open");
  m.paint(stroke);
  m.history.strokes.push_back(stroke);
  if (m.opt.schedule == ReparamSchedule::EachStroke && m.opt.adapt.mode != AdaptMode::None) m.reparameterize();
}

void PaintSession::begin_stroke(const Stroke& style) {
  Impl& m = *impl_;
  if (m.resampled) throw Error("paint session: interactive strokes are not supported in resample mode");
  m.painter->begin_stroke(style);
  if (m.base_painter) m.base_painter->begin_stroke(style);
  m.open_style = style;
  m.open_style.dabs.clear();
  m.open = true;
}

std::array<int, 4> PaintSession::add_dab(const Vec3& centre) {
  Impl& m = *impl_;
  const auto r = m.painter->add_dab(centre);
  if (m.base_painter) m.base_painter->add_dab(centre);
  m.open_dabs.push_back(centre);
  return r;
}

void PaintSession::end_stroke() {
  Impl& m = *impl_;
  m.painter->end_stroke();
  if (m.base_painter) m.base_painter->end_stroke();
  m.open = false;
  Stroke s = m.open_style;
  s.dabs = std::move(m.open_dabs);
  m.open_dabs.clear();
  if (s.dabs.empty()) return;
  m.history.strokes.push_back(std::move(s));
  if (m.opt.schedule == ReparamSchedule::EachStroke && m.opt.adapt.mode != AdaptMode::None) m.reparameterize();
}

void PaintSession::finish() {
  Impl& m = *impl_;
  if (m.opt.schedule == ReparamSchedule::End && m.opt.adapt.mode != AdaptMode::None) m.reparameterize();
}

const AdaptReport& PaintSession::reparameterize() { return impl_->reparameterize(); }
const TriMesh& PaintSession::mesh() const { return impl_->current_mesh(); }
const Parameterization& PaintSession::param() const { return *impl_->param; }
const ImageRGBA8& PaintSession::texture() { return impl_->texture(); }
const TexelMap& PaintSession::texel_map() const { return impl_->painter->texel_map(); }
const StrokeFile& PaintSession::history() const { return impl_->history; }
const std::vector<AdaptReport>& PaintSession::reports() const { return impl_->reports; }
const AdaptResult* PaintSession::last_result() const { return impl_->last.get(); }
const PaintSessionOptions& PaintSession::options() const { return impl_->opt; }
Painter& PaintSession::painter() { return *impl_->painter; }

double PaintSession::estimate_error() {
  Impl& m = *impl_;
  if (m.history.strokes.empty()) return 0;
  if (m.samples.empty()) m.samples = sample_surface(m.mesh, m.opt.safeguard_samples, 0x5eedada);
  if (m.refined && m.refined_samples.empty())  // refined without a safeguard run: sample it directly
    m.refined_samples = sample_surface(*m.refined, m.opt.safeguard_samples, 0x5eedada);
  StrokeSignal sig(m.current_mesh(), m.history);
  return m.estimate(*m.param, m.texture(), sig.evaluate(m.current_samples()));
}

}  // namespace adaptex
