#pragma once
/// \file uv_warp.h
/// A warp of the UV square as a value: what a method computes and what refinement, the remap, the
/// safeguard and a painting session apply. It is an exact part (every chart moved by a similarity,
/// atlas_flow.h; none for one chart) followed by a smooth map of the square. Two implementations:
/// LatticeWarp (bilinear lattices applied in turn, thesis §3.7.2) and FlowLayoutWarp (wedges advected
/// through the exact density flow, density_flow.h).
#include <memory>
#include <vector>

#include "adaptex/adapt/atlas_flow.h"
#include "adaptex/adapt/density_flow.h"
#include "adaptex/adapt/grid.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// The warp old uv → new uv of one re-parameterization. Immutable and thread-safe once built.
class UvWarp {
 public:
  /// \param moves one move per chart (empty: the charts stay) \param lattices the map's lattices, in
  /// application order (what pictures draw; LatticeWarp applies them)
  UvWarp(std::vector<ChartMove> moves, std::vector<GridWarp> lattices);
  virtual ~UvWarp();
  UvWarp(const UvWarp&) = delete;
  UvWarp& operator=(const UvWarp&) = delete;

  /// A point of the input layout warped: moved with its chart, then mapped.
  Vec2 apply(const Vec2& uv) const { return map(moves_.empty() ? uv : locator_.apply(uv)); }
  /// The smooth part alone, on the moved layout.
  virtual Vec2 map(const Vec2& uv) const = 0;
  /// \p layout (the input layout, or its refinement) with the exact part applied: the layout damping
  /// starts from. A copy of \p layout when no chart moves.
  Parameterization start_layout(const Parameterization& layout) const;
  /// \p start (a start_layout()) with every wedge mapped and damped by \p t: (1 − t)·identity + t·map
  /// (t = 1 the full warp, 0 \p start itself), clamped to [0,1]². What safe_remap_layout() gets.
  virtual Parameterization warp_layout(const Parameterization& start, double t = 1.0) const = 0;
  /// Largest |apply(p) − other.apply(p)| over \p points (0 for none).
  double deviation(const UvWarp& other, const std::vector<Vec2>& points) const;

  /// The chart moves (empty: one chart, or charts not moved).
  const std::vector<ChartMove>& chart_moves() const { return moves_; }
  /// Whether the warp moves charts: it changes the layout even fully damped.
  bool moves_charts() const { return !moves_.empty(); }
  /// The lattices, in application order ({coarse, fine}, {fine} or one per chart).
  const std::vector<GridWarp>& lattices() const { return lattices_; }

 protected:
  std::vector<ChartMove> moves_;
  ChartMoveLocator locator_;
  std::vector<GridWarp> lattices_;
};

/// Bilinear lattices applied in turn (WarpChain), each the identity outside its rectangle.
class LatticeWarp final : public UvWarp {
 public:
  explicit LatticeWarp(std::vector<GridWarp> lattices, std::vector<ChartMove> moves = {});
  Vec2 map(const Vec2& uv) const override { return chain_.apply(uv); }
  /// remap_parameterization() through every lattice blended by \p t (GridWarp::blended).
  Parameterization warp_layout(const Parameterization& start, double t = 1.0) const override;

 private:
  WarpChain chain_;
};

/// The exact flows (FlowWarp); the lattices sampled from them only draw pictures.
class FlowLayoutWarp final : public UvWarp {
 public:
  FlowLayoutWarp(FlowWarp flow, std::vector<GridWarp> lattices, std::vector<ChartMove> moves = {});
  Vec2 map(const Vec2& uv) const override { return flow_.apply(uv); }
  /// Every wedge advected (FlowWarp::apply_all), blended toward \p start by \p t (blend_layouts()).
  Parameterization warp_layout(const Parameterization& start, double t = 1.0) const override;

 private:
  FlowWarp flow_;
};

}  // namespace adaptex
