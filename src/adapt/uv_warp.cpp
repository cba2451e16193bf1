// UvWarp: the exact chart moves plus a smooth map of the square (lattices or exact flows).
#include "adaptex/adapt/uv_warp.h"

#include <algorithm>

#include "adaptex/adapt/remap.h"

namespace adaptex {

UvWarp::UvWarp(std::vector<ChartMove> moves, std::vector<GridWarp> lattices)
    : moves_(std::move(moves)), locator_(moves_), lattices_(std::move(lattices)) {}

UvWarp::~UvWarp() = default;

Parameterization UvWarp::start_layout(const Parameterization& layout) const {
  return moves_.empty() ? layout : move_charts(layout, moves_);
}

double UvWarp::deviation(const UvWarp& other, const std::vector<Vec2>& points) const {
  double d = 0;
  for (const Vec2& p : points) d = std::max(d, (apply(p) - other.apply(p)).norm());
  return d;
}

namespace {
std::vector<const GridWarp*> non_empty(const std::vector<GridWarp>& lattices) {
  std::vector<const GridWarp*> w;
  for (const GridWarp& g : lattices)
    if (g.n > 0) w.push_back(&g);
  return w;
}
}  // namespace

LatticeWarp::LatticeWarp(std::vector<GridWarp> lattices, std::vector<ChartMove> moves)
    : UvWarp(std::move(moves), std::move(lattices)), chain_(non_empty(lattices_)) {}

Parameterization LatticeWarp::warp_layout(const Parameterization& start, double t) const {
  if (t == 1.0) return remap_parameterization(start, non_empty(lattices_));
  std::vector<GridWarp> damped;
  for (const GridWarp* w : non_empty(lattices_)) damped.push_back(w->blended(t));
  std::vector<const GridWarp*> ptrs;
  for (const GridWarp& w : damped) ptrs.push_back(&w);
  return remap_parameterization(start, ptrs);
}

}  // namespace adaptex
