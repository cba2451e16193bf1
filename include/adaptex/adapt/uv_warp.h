#pragma once
/// \file uv_warp.h
/// A warp of the UV square as a value: what a method computes and what refinement, the remap, the
/// safeguard and a painting session apply. It is an exact part (every chart moved by a similarity,
/// atlas_flow.h; none for one chart) followed by a smooth map of the square: LatticeWarp (bilinear
/// lattices applied in turn, thesis §3.7.2).
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
  /// \param moves one per chart (empty: charts stay) \param lattices the map's, in application order
  UvWarp(std::vector<ChartMove> moves, std::vector<GridWarp> lattices);
  virtual ~UvWarp();
  UvWarp(const UvWarp&) = delete;
  UvWarp& operator=(const UvWarp&) = delete;

  Vec2 apply(const Vec2& uv) const { return map(moves_.empty() ? uv : locator_.apply(uv)); }  ///< Move, then map.
  virtual Vec2 map(const Vec2& uv) const = 0;  ///< The smooth part alone, on the moved layout.
  Parameterization start_layout(const Parameterization& layout) const;  ///< \p layout with the charts moved.
  /// \p start with every wedge mapped, damped by \p t ((1 − t)·identity + t·map), clamped to [0,1]².
  virtual Parameterization warp_layout(const Parameterization& start, double t = 1.0) const = 0;
  double deviation(const UvWarp& other, const std::vector<Vec2>& points) const;  ///< Max |apply − other.apply|.

  const std::vector<ChartMove>& chart_moves() const { return moves_; }  ///< Empty: charts not moved.
  bool moves_charts() const { return !moves_.empty(); }
  const std::vector<GridWarp>& lattices() const { return lattices_; }  ///< In application order.

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
  Parameterization warp_layout(const Parameterization& start, double t = 1.0) const override;

 private:
  WarpChain chain_;
};

}  // namespace adaptex
