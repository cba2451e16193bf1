#pragma once
/// \file eval.h
/// Signal approximation error of a texture against the exact painted signal (stroke-file contract,
/// shared/docs/strokes.md "Reconstruction from a texture"): MSE and PSNR over points spread uniformly
/// by surface area. Used by `adaptex eval` and every quality experiment.
#include <cstdint>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/progress.h"
#include "adaptex/paint/signal.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {

/// Settings of evaluate_texture().
struct EvalOptions {
  /// Number K of surface samples. 10^6 gives PSNR to about +-0.01 dB and takes well under 2 s.
  long long samples = 1000000;
  /// Seed of the sample positions (same seed, mesh and K: the same points, bit for bit).
  std::uint64_t seed = 1;
  /// Called with ("eval", fraction) on the calling thread as the samples are evaluated (in about 32
  /// steps); returning false cancels: evaluate_texture() throws CancelledError. Empty: no reports.
  ProgressCallback progress;
};

/// Result of evaluate_texture().
struct EvalResult {
  double mse = 0;        ///< Mean over samples and the 3 channels of the squared difference, RGB in [0,1].
  double psnr = 0;       ///< 10 log10(1 / mse) in dB; 200 when mse < 1e-20 (exact reconstruction).
  long long samples = 0; ///< K.
  std::uint64_t seed = 0;
};

/// PSNR in dB of an MSE of values in [0,1]: 10 log10(1 / mse), 200 when mse < 1e-20 (exact).
double psnr_from_mse(double mse);

/// K points uniformly distributed by surface area (face chosen with probability area/total, then a
/// uniform point in the face). Sample k depends only on (seed, k): reproducible and parallel.
/// \pre mesh has at least one face of positive area. \throw InvalidInputError otherwise
std::vector<SurfacePoint> sample_surface(const TriMesh& mesh, long long count, std::uint64_t seed);

/// MSE (mean over the points and the 3 channels, RGB in [0,1]) of the reconstruction of \p texture at
/// \p points (uv interpolated from \p param's corner UVs, then sample_bilinear, as evaluate_texture)
/// against \p exact[k], the exact signal at points[k]. For callers that keep a fixed set of points and
/// their exact values, e.g. the safeguard of adapt/session.h. Deterministic (fixed summation order).
/// \return 0 when \p points is empty
/// \pre every points[k].face indexes param.uv_faces
/// \throw InvalidInputError exact.size() != points.size(), or an empty texture with points
double reconstruction_mse(const Parameterization& param, const ImageRGBA8& texture,
                          const std::vector<SurfacePoint>& points, const std::vector<Vec3>& exact);

/// MSE/PSNR of the texture \p texture on \p param against the exact signal of \p strokes: the
/// reconstruction at a sample is sample_bilinear(texture, uv) with uv interpolated from the face's
/// corner UVs (bilinear, clamp-to-edge, texel centres at (i+0.5)/W, v = 0 bottom row).
/// Parallel (TBB), deterministic (fixed summation order).
/// \throw InvalidInputError empty texture, param not matching the mesh, K < 1
/// \throw CancelledError options.progress returned false
EvalResult evaluate_texture(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                            const StrokeFile& strokes, const EvalOptions& options = {});

}  // namespace adaptex
