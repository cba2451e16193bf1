/// \file material_eval.cpp
/// Every channel of a material's textures against the exact material on surface samples; the
/// height judged through its shading normal, from forward differences of the exact height.
#include "adaptex/paint/material_eval.h"

#include <cmath>

#include <tbb/parallel_for.h>

#include "adaptex/core/errors.h"
#include "adaptex/core/image.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/material_signal.h"
#include "adaptex/paint/tangent_frame.h"

namespace adaptex {

namespace {

/// The barycentric offset (d0, d1) of a 3-D step \p delta in the plane of face \p f.
Vec2 barycentric_step(const TriMesh& mesh, int f, const Vec3& delta) {
  const auto& t = mesh.faces[f];
  const Vec3 e1 = mesh.positions[t[1]] - mesh.positions[t[0]], e2 = mesh.positions[t[2]] - mesh.positions[t[0]];
  const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2), det = a * c - b * b;
  if (!(det > 0)) return Vec2::Zero();
  const double r1 = delta.dot(e1), r2 = delta.dot(e2);
  const double d1 = (c * r1 - b * r2) / det, d2 = (a * r2 - b * r1) / det;  // delta = d1 e1 + d2 e2
  return Vec2(-d1 - d2, d1);
}

/// Two orthonormal directions in the plane of face \p f (zero for a degenerate face).
std::array<Vec3, 2> face_directions(const TriMesh& mesh, int f) {
  const auto& t = mesh.faces[f];
  const Vec3 e1 = mesh.positions[t[1]] - mesh.positions[t[0]], e2 = mesh.positions[t[2]] - mesh.positions[t[0]];
  const Vec3 n = e1.cross(e2);
  if (!(n.norm() > 0) || !(e1.norm() > 0)) return {Vec3::Zero(), Vec3::Zero()};
  const Vec3 u = e1.normalized();
  return {u, n.normalized().cross(u)};
}

/// The A channel of \p img bilinearly at the taps (x, y) (this file's alpha lookup).
double bilinear_alpha(const ImageRGBA8& img, const BilinearTap& x, const BilinearTap& y) {
  auto at = [&img](int i, int j) { return img.data[4 * (static_cast<size_t>(j) * img.width + i) + 3] / 255.0; };
  return (1 - y.f) * ((1 - x.f) * at(x.i0, y.i0) + x.f * at(x.i1, y.i0)) +
         y.f * ((1 - x.f) * at(x.i0, y.i1) + x.f * at(x.i1, y.i1));
}

/// Channel \p c of \p img bilinearly at the taps (x, y), in [0, 1]: sample_bilinear()'s arithmetic,
/// so that the textures of one size share one pair of taps per point.
double bilinear_channel(const ImageRGBA8& img, const BilinearTap& x, const BilinearTap& y, int c) {
  const double a = img.texel(x.i0, y.i0)[c], b = img.texel(x.i1, y.i0)[c];
  const double d = img.texel(x.i0, y.i1)[c], e = img.texel(x.i1, y.i1)[c];
  const double bottom = a + (b - a) * x.f, top = d + (e - d) * x.f;
  return (bottom + (top - bottom) * y.f) / 255.0;
}

/// bilinear_channel() of channels 0, 1, 2, the four texels located once.
Vec3 bilinear_rgb(const ImageRGBA8& img, const BilinearTap& x, const BilinearTap& y) {
  const std::uint8_t *p00 = img.texel(x.i0, y.i0), *p10 = img.texel(x.i1, y.i0);
  const std::uint8_t *p01 = img.texel(x.i0, y.i1), *p11 = img.texel(x.i1, y.i1);
  Vec3 out;
  for (int c = 0; c < 3; ++c) {
    const double a = p00[c], b = p10[c], d = p01[c], e = p11[c];
    const double bottom = a + (b - a) * x.f, top = d + (e - d) * x.f;
    out[c] = (bottom + (top - bottom) * y.f) / 255.0;
  }
  return out;
}

/// True when some stroke of \p file paints or erases height (else the height is flat everywhere).
bool paints_height(const MaterialStrokeFile& file) {
  for (const MaterialLayer& layer : file.layers)
    for (const MaterialStroke& s : layer.strokes)
      if (s.channels & channel_bit(Channel::Height)) return true;
  return false;
}

void check_inputs(const TriMesh& mesh, const Parameterization& param, const MaterialTextures& tex,
                  const MaterialEvalOptions& o) {
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("evaluate_material_textures: the layout and the mesh have different face counts");
  if (o.samples < 1) throw InvalidInputError("evaluate_material_textures: samples must be >= 1");
  if (!(o.gradient_step > 0) || !(o.data_weight >= 0) || !std::isfinite(o.data_weight))
    throw InvalidInputError("evaluate_material_textures: gradient_step must be > 0 and data_weight >= 0");
  for (const ImageRGBA8* img : {&tex.base_color, &tex.roughness, &tex.metallic, &tex.normal})
    if (img->width < 1 || img->height < 1 || img->width != tex.base_color.width || img->height != tex.base_color.height)
      throw InvalidInputError("evaluate_material_textures: the textures must be non-empty and of one size");
}

}  // namespace

MaterialEvalPoints material_eval_points(const TriMesh& mesh, bool with_height, const MaterialEvalOptions& options) {
  if (options.samples < 1) throw InvalidInputError("evaluate_material_textures: samples must be >= 1");
  if (!(options.gradient_step > 0)) throw InvalidInputError("evaluate_material_textures: gradient_step must be > 0");
  MaterialEvalPoints out;
  out.samples = sample_surface(mesh, options.samples, options.seed);
  const size_t K = out.samples.size();
  // Each sample, and where the height varies, two steps of eps along two directions of its face: the
  // exact height's gradient by forward differences (eps is far below any texel: their O(eps) error is
  // negligible, and they cost 3 evaluations per sample instead of central differences' 5).
  const int P = out.per_sample = with_height ? 3 : 1;
  const double eps = out.step = options.gradient_step * bounding_box(mesh).diagonal();
  out.probes.resize(P * K);
  out.directions.assign(K, {Vec3::Zero(), Vec3::Zero()});
  tbb::parallel_for(size_t(0), K, [&](size_t k) {
    const SurfacePoint& p = out.samples[k];
    out.probes[P * k] = p;
    if (P == 1) return;
    out.directions[k] = face_directions(mesh, p.face);
    for (int a = 0; a < 2; ++a) {
      const Vec2 d = barycentric_step(mesh, p.face, eps * out.directions[k][a]);
      out.probes[P * k + 1 + a] = SurfacePoint{p.face, p.b0 + d.x(), p.b1 + d.y()};
    }
  });
  return out;
}

MaterialError evaluate_material_textures(const TriMesh& mesh, const Parameterization& param,
                                         const MaterialTextures& textures, const MaterialStrokeFile& file,
                                         const MaterialEvalOptions& options) {
  check_inputs(mesh, param, textures, options);
  const MaterialEvalPoints pts = material_eval_points(mesh, paints_height(file), options);
  return evaluate_material_textures(mesh, param, textures, pts, evaluate_material(mesh, file, pts.probes), options);
}

namespace {

/// Per sample: squared errors of base colour, alpha, roughness, metallic, normal; and the albedo².
using SampleTerms = std::array<double, 6>;

/// What the per-sample terms read besides the textures and the exact values: the mesh's vertex
/// normals and the layout's wedge tangents (the frames of the exact normals).
struct FrameTerms {
  std::vector<Vec3> vn;
  std::vector<Eigen::Vector4d> tangents;
};

FrameTerms frame_terms(const TriMesh& mesh, const Parameterization& param) {
  FrameTerms f;
  f.vn = vertex_normals(mesh);
  f.tangents = wedge_tangents(mesh, param, f.vn);
  return f;
}

/// The frames sample_terms() reads: the vertex normals and wedge tangents of \p own or of \p terms.
struct FrameView {
  const std::vector<Vec3>& vn;
  const std::vector<Eigen::Vector4d>& tangents;
};

void check_exact(const MaterialEvalPoints& points, const std::vector<MaterialValue>& exact) {
  const size_t K = points.samples.size();
  if (exact.size() != points.per_sample * K || points.directions.size() != K)
    throw InvalidInputError("evaluate_material_textures: one exact value per probe point expected");
}

/// The terms of sample \p k (evaluate_material_textures()).
SampleTerms sample_terms(const TriMesh& mesh, const Parameterization& param, const MaterialTextures& textures,
                         const MaterialEvalPoints& points, const std::vector<MaterialValue>& exact,
                         const FrameView& frames, size_t k) {
  const SurfacePoint& p = points.samples[k];
  const int P = points.per_sample;
  const double eps = points.step;
  const auto& dirs = points.directions;
  const Face& t = param.uv_faces[p.face];
  const Vec2 uv = p.b0 * param.uv[t[0]] + p.b1 * param.uv[t[1]] + (1 - p.b0 - p.b1) * param.uv[t[2]];
  const MaterialValue& e = exact[P * k];
  // One pair of taps for every map (check_inputs(): one size).
  const BilinearTap tx = bilinear_tap(textures.base_color.width, uv.x());
  const BilinearTap ty = bilinear_tap(textures.base_color.height, uv.y());
  const Vec3 c = bilinear_rgb(textures.base_color, tx, ty);
  const Vec3 ce(e[0], e[1], e[2]);
  const double a = bilinear_alpha(textures.base_color, tx, ty);
  const double r = bilinear_channel(textures.roughness, tx, ty, 0);
  const double m = bilinear_channel(textures.metallic, tx, ty, 0);
  const double scale = textures.height_scale;
  const Vec3 grad = P == 1 ? Vec3::Zero().eval()
                           : Vec3(scale * ((exact[P * k + 1][6] - e[6]) / eps * dirs[k][0] +
                                           (exact[P * k + 2][6] - e[6]) / eps * dirs[k][1]));
  Vec3 n_exact(0, 0, 1);  // a flat exact height: the surface's own normal, in any frame
  if (!grad.isZero(0)) {
    const TangentFrame fr = interpolated_frame(mesh, param, frames.vn, frames.tangents, p.face, p.b0, p.b1);
    n_exact = Vec3(-grad.dot(fr.t), -grad.dot(fr.b), 1).normalized();
  }
  const Vec3 n_tex = bilinear_rgb(textures.normal, tx, ty);
  return {(c - ce).squaredNorm() / 3,     std::pow(a - e[3], 2), std::pow(r - e[4], 2), std::pow(m - e[5], 2),
          (n_tex - 0.5 * (n_exact + Vec3::Ones())).squaredNorm() / 3, ce.squaredNorm() / 3};
}

/// The means of the per-sample terms, summed in sample order (deterministic), and their weighting.
MaterialError sum_errors(const std::vector<SampleTerms>& err, const MaterialEvalOptions& options) {
  std::array<double, 6> sum{};
  for (const auto& x : err)  // fixed order: deterministic
    for (int j = 0; j < 6; ++j) sum[j] += x[j];
  for (double& s : sum) s /= static_cast<double>(err.size());
  MaterialError out;
  out.base_color = sum[0];
  out.alpha = sum[1];
  out.roughness = sum[2];
  out.metallic = sum[3];
  out.normal = sum[4];
  out.normal_weight = std::max(4 * sum[5], 1e-6);
  out.weighted = out.base_color + options.data_weight * (out.alpha + out.roughness + out.metallic) / 3 +
                 out.normal_weight * out.normal;
  return out;
}

}  // namespace

MaterialError evaluate_material_textures(const TriMesh& mesh, const Parameterization& param,
                                         const MaterialTextures& textures, const MaterialEvalPoints& points,
                                         const std::vector<MaterialValue>& exact, const MaterialEvalOptions& options,
                                         const HeightNormalTerms* terms) {
  check_inputs(mesh, param, textures, options);
  check_exact(points, exact);
  if (terms && (terms->vertex_normals.size() != mesh.positions.size() || terms->tangents.size() != static_cast<size_t>(param.num_wedges())))
    throw InvalidInputError("evaluate_material_textures: the frame terms are of another mesh or layout");
  const FrameTerms own = terms ? FrameTerms{} : frame_terms(mesh, param);
  const FrameView frames = terms ? FrameView{terms->vertex_normals, terms->tangents} : FrameView{own.vn, own.tangents};
  std::vector<SampleTerms> err(points.samples.size());
  tbb::parallel_for(size_t(0), err.size(), [&](size_t k) {
    err[k] = sample_terms(mesh, param, textures, points, exact, frames, k);
  });
  return sum_errors(err, options);
}

struct MaterialErrorTracker::Impl {
  FrameTerms frames;
  std::vector<SampleTerms> err;
  bool fresh = true;
};

MaterialErrorTracker::MaterialErrorTracker() : impl_(std::make_unique<Impl>()) {}
MaterialErrorTracker::~MaterialErrorTracker() = default;
MaterialErrorTracker::MaterialErrorTracker(MaterialErrorTracker&&) noexcept = default;
MaterialErrorTracker& MaterialErrorTracker::operator=(MaterialErrorTracker&&) noexcept = default;

void MaterialErrorTracker::reset() { impl_->fresh = true; }

MaterialError MaterialErrorTracker::evaluate(const TriMesh& mesh, const Parameterization& param,
                                             const MaterialTextures& textures, const MaterialEvalPoints& points,
                                             const std::vector<MaterialValue>& exact,
                                             const std::vector<char>& changed_probes,
                                             const std::vector<char>& changed_texels, const MaterialEvalOptions& options) {
  check_inputs(mesh, param, textures, options);
  check_exact(points, exact);
  Impl& m = *impl_;
  const size_t K = points.samples.size(), texels = textures.base_color.data.size() / 4;
  const int P = points.per_sample;
  const bool all = m.fresh || m.err.size() != K;
  if (!all && (changed_probes.size() != exact.size() || changed_texels.size() != texels))
    throw InvalidInputError("material error tracker: one flag per probe and per texel expected");
  if (all) m.frames = frame_terms(mesh, param), m.err.resize(K);
  const int W = textures.base_color.width, H = textures.base_color.height;
  tbb::parallel_for(size_t(0), K, [&](size_t k) {
    if (!all) {
      bool stale = false;
      for (int q = 0; q < P; ++q) stale = stale || changed_probes[P * k + q];
      if (!stale) {  // the four texels of the sample's taps (as sample_terms()'s)
        const SurfacePoint& p = points.samples[k];
        const Face& t = param.uv_faces[p.face];
        const Vec2 uv = p.b0 * param.uv[t[0]] + p.b1 * param.uv[t[1]] + (1 - p.b0 - p.b1) * param.uv[t[2]];
        const BilinearTap tx = bilinear_tap(W, uv.x()), ty = bilinear_tap(H, uv.y());
        for (int j : {ty.i0, ty.i1})
          for (int i : {tx.i0, tx.i1}) stale = stale || changed_texels[static_cast<size_t>(j) * W + i];
      }
      if (!stale) return;
    }
    m.err[k] = sample_terms(mesh, param, textures, points, exact, FrameView{m.frames.vn, m.frames.tangents}, k);
  });
  m.fresh = false;
  return sum_errors(m.err, options);
}

}  // namespace adaptex
