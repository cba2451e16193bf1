// PaintSession: the painting loop with signal-adaptive re-parameterization (thesis Fig. 3.1).
#include "adaptex/adapt/session.h"

#include <tbb/parallel_reduce.h>
#include <tbb/blocked_range.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "adaptex/adapt/stretch_map.h"
#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/padding.h"
#include "adaptex/paint/signal.h"

namespace adaptex {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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
  TriMesh mesh;
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
    segment = std::make_unique<Segment>(Segment{Painter(mesh, *param, po, Vec3(0, 0, 0)),
                                                Painter(mesh, *param, po, Vec3(1, 1, 1)), true});
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
    return reconstruction_mse(p, tex, samples, exact);
  }

  const AdaptReport& reparameterize() {
    const auto t_all = std::chrono::steady_clock::now();
    AdaptOptions ao = opt.adapt;
    if (ao.mode == AdaptMode::None) ao.mode = AdaptMode::TwoStage;  // explicit request
    const ImageRGBA8& tex = texture();
    const Parameterization& src = base_param ? *base_param : *param;
    auto res = std::make_unique<AdaptResult>(
        base_painter ? adapt_parameterization(mesh, src, base_painter->texture(), base_painter->texel_map(), ao)
                     : adapt_parameterization(mesh, src, tex, painter->texel_map(), ao));
    AdaptReport& rep = res->report;
    if (!opt.debug_dir.empty())
      write_debug_maps(opt.debug_dir, "reparam" + std::to_string(reparam_count), *res);
    ++reparam_count;
    if (!rep.accepted || rep.damping == 0) {
      rep.time_total = seconds_since(t_all);
      reports.push_back(rep);
      last = std::move(res);
      return reports.back();
    }
    const PainterOptions po = painter_options(history.background);
    const bool use_safeguard = opt.safeguard && !history.strokes.empty();
    std::vector<Vec3> exact;
    auto t0 = std::chrono::steady_clock::now();
    if (use_safeguard) {
      if (samples.empty()) samples = sample_surface(mesh, opt.safeguard_samples, 0x5eedada);
      StrokeSignal sig(mesh, history);
      exact = sig.evaluate(samples);
      rep.error_before = estimate(*param, tex, exact);
    }
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
        np = std::make_unique<Parameterization>(safe_remap(src, ptrs, ao.remap).param);
      }
      auto tm = std::chrono::steady_clock::now();
      npainter = std::make_unique<Painter>(mesh, *np, po, history.background);
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
      rep.error_after = estimate(*np, ntex, exact);
      const double limit = rep.error_before * (1.0 - opt.safeguard_margin);
      accept = rep.error_after < limit;
      rep.time_safeguard += seconds_since(t0);
      if (!accept) {
        std::unique_ptr<Parameterization> hp;
        std::unique_ptr<Painter> hpainter;
        ImageRGBA8 htex;
        make(0.5, hp, hpainter, htex);
        t0 = std::chrono::steady_clock::now();
        const double eh = estimate(*hp, htex, exact);
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
      res->param = *np;
      painter = std::move(npainter);  // references *np: keep np alive as the new param
      param = std::move(np);
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
      res->param = *param;
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
  if (options.texture_size < 1 || options.texture_size > 16384)
    throw InvalidInputError("paint session: texture size must be in [1, 16384], got " +
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
const TriMesh& PaintSession::mesh() const { return impl_->mesh; }
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
  StrokeSignal sig(m.mesh, m.history);
  return m.estimate(*m.param, m.texture(), sig.evaluate(m.samples));
}

void to_json(nlohmann::json& j, const AdaptReport& r) {
  j = nlohmann::json{{"mode", to_string(r.mode)},
                     {"accepted", r.accepted},
                     {"damping", r.damping},
                     {"global_damping", r.global_damping},
                     {"locally_damped_wedges", r.locally_damped},
                     {"l2_before", r.l2_before},
                     {"l2_after", r.l2_after},
                     {"coarse_iterations", r.coarse_iterations},
                     {"fine_iterations", r.fine_iterations},
                     {"remap_checks", r.remap_checks},
                     {"flipped_after", r.flipped_after},
                     {"degenerate_after", r.degenerate_after},
                     {"signal_fraction", r.signal_fraction},
                     {"time_ms",
                      {{"importance", 1e3 * r.time_importance},
                       {"stretch_map", 1e3 * r.time_stretch_map},
                       {"ls2", 1e3 * r.time_ls2},
                       {"coarse", 1e3 * r.time_coarse},
                       {"fine", 1e3 * r.time_fine},
                       {"remap", 1e3 * r.time_remap},
                       {"texel_map", 1e3 * r.time_texel_map},
                       {"texture_update", 1e3 * r.time_texture_update},
                       {"safeguard", 1e3 * r.time_safeguard},
                       {"total", 1e3 * r.time_total}}}};
  if (r.error_before >= 0) {
    j["mse_before"] = r.error_before;
    j["mse_after"] = r.error_after;
  }
}

nlohmann::json adapt_reports_json(const std::vector<AdaptReport>& reports) {
  nlohmann::json arr = nlohmann::json::array();
  double total = 0;
  int accepted = 0;
  for (const auto& r : reports) {
    arr.push_back(r);
    total += r.time_total;
    accepted += r.accepted ? 1 : 0;
  }
  return {{"count", reports.size()}, {"accepted", accepted}, {"total_ms", 1e3 * total}, {"reports", arr}};
}

namespace {
ImageRGBA8 grey(const ImageF& img) {
  ImageRGBA8 out(img.width, img.height, {0, 0, 0, 255});
  for (size_t k = 0; k < img.data.size(); ++k) {
    const auto v = static_cast<std::uint8_t>(std::lround(std::clamp(img.data[k], 0.0f, 1.0f) * 255));
    out.data[4 * k] = out.data[4 * k + 1] = out.data[4 * k + 2] = v;
  }
  return out;
}
void draw_line(ImageRGBA8& img, Vec2 a, Vec2 b, std::array<std::uint8_t, 3> c) {
  const double len = std::max(std::abs(b.x() - a.x()) * img.width, std::abs(b.y() - a.y()) * img.height);
  const int steps = std::max(1, static_cast<int>(std::ceil(len)));
  for (int s = 0; s <= steps; ++s) {
    const Vec2 p = a + (b - a) * (double(s) / steps);
    const int i = std::clamp(static_cast<int>(p.x() * img.width), 0, img.width - 1);
    const int j = std::clamp(static_cast<int>(p.y() * img.height), 0, img.height - 1);
    std::uint8_t* px = img.texel(i, j);
    px[0] = c[0];
    px[1] = c[1];
    px[2] = c[2];
  }
}
ImageRGBA8 draw_grid(const ImageF& under, const GridWarp& g, int max_lines) {
  ImageRGBA8 img = grey(under);
  const int step = std::max(1, g.n / max_lines);
  for (int j = 0; j <= g.n; ++j)
    for (int i = 0; i <= g.n; ++i) {
      if (j % step == 0 && i < g.n) draw_line(img, g.at(i, j), g.at(std::min(g.n, i + 1), j), {220, 30, 30});
      if (i % step == 0 && j < g.n) draw_line(img, g.at(i, j), g.at(i, std::min(g.n, j + 1)), {220, 30, 30});
    }
  return img;
}
}  // namespace

void write_debug_maps(const std::filesystem::path& dir, const std::string& prefix, const AdaptResult& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw IoError(dir.string() + ": cannot create the debug-map directory: " + ec.message());
  if (!r.importance.data.empty()) write_png(dir / (prefix + "_importance.png"), grey(r.importance));
  if (!r.stretch.data.empty()) write_png(dir / (prefix + "_stretch.png"), grey(r.stretch));
  if (!r.ls2.data.empty()) {
    write_png(dir / (prefix + "_ls2.png"), grey(r.ls2));
    if (r.coarse.n > 0) write_png(dir / (prefix + "_grid_coarse.png"), draw_grid(r.ls2, r.coarse, 64));
    if (r.fine.n > 0) write_png(dir / (prefix + "_grid_fine.png"), draw_grid(r.ls2, r.fine, 64));
  }
}

}  // namespace adaptex
