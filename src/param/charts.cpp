/// \file charts.cpp
/// Segmentation into charts by seeded region growing with Lloyd re-seeding (docs/charts.md).
#include "adaptex/param/charts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/topology.h"

namespace adaptex {

namespace {


/// Dual graph of the faces in CSR form: neighbours across shared (two-face) edges.
struct DualGraph {
  std::vector<int> offsets, nbr;
  std::vector<double> length;  ///< Distance between the two face centroids.
  std::vector<Vec3> centroid, normal;
  std::vector<double> area;
};

DualGraph build_dual_graph(const TriMesh& mesh) {
  const int nf = mesh.num_faces();
  const EdgeConnectivity ec = build_edges(mesh);
  DualGraph g;
  g.centroid.resize(nf);
  g.normal.resize(nf);
  g.area.resize(nf);
  for (int f = 0; f < nf; ++f) {
    const Face& t = mesh.faces[f];
    g.centroid[f] = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
    g.normal[f] = face_normal(mesh, f);
    g.area[f] = face_area(mesh, f);
  }
  g.offsets.assign(nf + 1, 0);
  for (const auto& ef : ec.edge_faces)
    if (ef.size() == 2) ++g.offsets[ef[0] + 1], ++g.offsets[ef[1] + 1];
  for (int f = 0; f < nf; ++f) g.offsets[f + 1] += g.offsets[f];
  g.nbr.resize(g.offsets[nf]);
  g.length.resize(g.offsets[nf]);
  std::vector<int> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (const auto& ef : ec.edge_faces) {
    if (ef.size() != 2) continue;
    const double d = (g.centroid[ef[0]] - g.centroid[ef[1]]).norm();
    g.nbr[fill[ef[0]]] = ef[1];
    g.length[fill[ef[0]]++] = d;
    g.nbr[fill[ef[1]]] = ef[0];
    g.length[fill[ef[1]]++] = d;
  }
  return g;
}

/// Min-queue of (distance, face) pairs, smallest pair first (ties by face id, as a
/// std::priority_queue with std::greater would pop them, so the growth is the same): a 4-ary
/// heap, shallower than a binary one.
class FaceQueue {
 public:
  using Item = std::pair<double, int>;
  bool empty() const { return heap_.empty(); }
  const Item& top() const { return heap_.front(); }
  void push(Item x) {
    size_t i = heap_.size();
    heap_.push_back(x);
    while (i > 0) {
      const size_t parent = (i - 1) / 4;
      if (!(x < heap_[parent])) break;
      heap_[i] = heap_[parent];
      i = parent;
    }
    heap_[i] = x;
  }
  void pop() {
    const Item x = heap_.back();
    heap_.pop_back();
    const size_t n = heap_.size();
    if (n == 0) return;
    size_t i = 0;
    for (;;) {
      const size_t first = 4 * i + 1;
      if (first >= n) break;
      size_t best = first;
      for (size_t c = first + 1; c < std::min(first + 4, n); ++c)
        if (heap_[c] < heap_[best]) best = c;
      if (!(heap_[best] < x)) break;
      heap_[i] = heap_[best];
      i = best;
    }
    heap_[i] = x;
  }

 private:
  std::vector<Item> heap_;
};

/// Dijkstra over the dual graph from the faces in \p pq: \p step_cost(f, k) is the cost of adjacency
/// entry k of face f; \p on_lower(f, h) is called when face h gets a lower distance through f.
template <class Cost, class OnLower>
void run_dijkstra(const DualGraph& g, FaceQueue& pq, Cost step_cost, std::vector<double>& dist,
                  OnLower on_lower) {
  while (!pq.empty()) {
    const auto [d, f] = pq.top();
    pq.pop();
    if (d > dist[f]) continue;
    for (int k = g.offsets[f]; k < g.offsets[f + 1]; ++k) {
      const int h = g.nbr[k];
      const double nd = d + step_cost(f, k);
      if (nd < dist[h]) {
        dist[h] = nd;
        on_lower(f, h);
        pq.push({nd, h});
      }
    }
  }
}

/// Multi-source Dijkstra over the dual graph. \p step_cost(label, k) is the cost of adjacency
/// entry k when growing chart \p label. Fills dist and label (-1 where unreachable).
template <class Cost>
void grow(const DualGraph& g, const std::vector<int>& seeds, Cost step_cost,
          std::vector<double>& dist, std::vector<int>& label) {
  const int nf = static_cast<int>(g.centroid.size());
  dist.assign(nf, kInf);
  label.assign(nf, -1);
  FaceQueue pq;
  for (size_t s = 0; s < seeds.size(); ++s) {
    dist[seeds[s]] = 0;
    label[seeds[s]] = static_cast<int>(s);
    pq.push({0.0, seeds[s]});
  }
  run_dijkstra(
      g, pq, [&](int f, int k) { return step_cost(label[f], k); }, dist,
      [&](int f, int h) { label[h] = label[f]; });
}

/// Lowers \p dist (plain dual distance to a set of seeds) to the distance to that set plus face
/// \p seed: a Dijkstra from the new seed alone that goes on only where the distance drops, so it
/// visits the new seed's Voronoi cell instead of every face. The distances are the minima over the
/// same path sums as a multi-source Dijkstra from all seeds (floating-point addition is monotone),
/// so they are bit-identical to it.
void add_seed_distance(const DualGraph& g, int seed, std::vector<double>& dist) {
  FaceQueue pq;
  dist[seed] = 0;
  pq.push({0.0, seed});
  run_dijkstra(
      g, pq, [&](int, int k) { return g.length[k]; }, dist, [](int, int) {});
}

/// Farthest-point seeds: the face farthest from face 0, then repeatedly the face farthest from all
/// seeds so far (plain centroid distance; the distance to the seeds is updated per new seed,
/// add_seed_distance()). The seeds of k charts are the first k of any longer sequence, so the
/// sequence is kept and extended on demand (ChartSegmenter reuses it across chart counts).
struct FarthestPoints {
  std::vector<int> seeds;
  std::vector<double> dist;  ///< Distance to the seeds so far.
  bool exhausted = false;    ///< Every face is at distance 0 (or unreachable): no more seeds.

  int farthest() const {
    int best = 0;
    for (size_t f = 0; f < dist.size(); ++f)
      if (dist[f] < kInf && dist[f] > dist[best]) best = static_cast<int>(f);
    return best;
  }
  /// The first min(k, available) seeds.
  std::vector<int> first(const DualGraph& g, int k) {
    if (seeds.empty()) {
      dist.assign(g.centroid.size(), kInf);
      add_seed_distance(g, 0, dist);
      seeds.push_back(farthest());
      std::fill(dist.begin(), dist.end(), kInf);
      add_seed_distance(g, seeds.back(), dist);
    }
    while (static_cast<int>(seeds.size()) < k && !exhausted) {
      const int f = farthest();
      if (dist[f] <= 0) {  // every face is a seed already
        exhausted = true;
        break;
      }
      seeds.push_back(f);
      add_seed_distance(g, f, dist);
    }
    return {seeds.begin(), seeds.begin() + std::min<size_t>(k, seeds.size())};
  }
};

/// The centre of every chart: the face farthest (plain dual distance) from the chart's border.
std::vector<int> chart_centres(const DualGraph& g, const std::vector<int>& label, int k) {
  const int nf = static_cast<int>(label.size());
  std::vector<int> border;
  for (int f = 0; f < nf; ++f) {
    bool on_border = g.offsets[f + 1] - g.offsets[f] < 3;  // touches the mesh boundary
    for (int j = g.offsets[f]; j < g.offsets[f + 1]; ++j) on_border |= label[g.nbr[j]] != label[f];
    if (on_border) border.push_back(f);
  }
  std::vector<double> dist;
  std::vector<int> nearest;
  // Every path out of a chart crosses its border faces, so the nearest border face of a face is one
  // of its own chart's.
  auto inside = [&](int, int j) { return g.length[j]; };
  std::vector<int> centre(k, -1);
  std::vector<double> best(k, -1.0);
  if (border.empty()) return centre;
  grow(g, border, inside, dist, nearest);
  for (int f = 0; f < nf; ++f)
    if (dist[f] < kInf && dist[f] > best[label[f]]) best[label[f]] = dist[f], centre[label[f]] = f;
  return centre;
}

/// Smooths chart borders. An "ear" of a chart is a vertex where the chart has a single face while
/// other charts (or the mesh boundary) take the rest of its fan: the disk embedding must make such a
/// vertex a corner of the square (Floater's one-to-one condition), and with more than four of them
/// it falls back to the circle and flattens the ear faces into slivers of huge stretch. Each such
/// face moves to the chart that has the most faces at that vertex; repeated until nothing moves
/// (bounded). Ears of the mesh itself (a vertex with one face) cannot be removed.
/// \p vf = build_vertex_faces(mesh).
void remove_ears(const TriMesh& mesh, const VertexFaces& vf, std::vector<int>& label) {
  const int nv = mesh.num_vertices();
  // A vertex whose fan kept its labels since its last visit, which moved nothing, would move
  // nothing again: only vertices with a changed fan (dirty) are visited, in the same order, so the
  // moves are those of visiting every vertex.
  std::vector<char> dirty(nv, 1);
  for (int pass = 0; pass < 20; ++pass) {
    bool moved = false;
    for (int v = 0; v < nv; ++v) {
      if (!dirty[v]) continue;
      dirty[v] = 0;
      const int b = vf.offsets[v], e = vf.offsets[v + 1];
      if (e - b < 2) continue;
      for (int i = b; i < e; ++i) {
        const int f = vf.faces[i], l = label[f];
        int same = 0, best = -1, best_count = 0;
        for (int j = b; j < e; ++j) same += label[vf.faces[j]] == l;
        if (same != 1) continue;
        for (int j = b; j < e; ++j) {
          const int o = label[vf.faces[j]];
          if (o == l) continue;
          int count = 0;
          for (int q = b; q < e; ++q) count += label[vf.faces[q]] == o;
          if (count > best_count) best = o, best_count = count;
        }
        if (best >= 0) {
          label[f] = best;
          moved = true;
          for (int w : mesh.faces[f]) dirty[w] = 1;
        }
      }
    }
    if (!moved) break;
  }
}

/// Relabels every edge-connected part of a chart as a chart (numbered in order of first face;
/// labels left without faces disappear). Returns the number of charts.
int split_into_parts(const DualGraph& g, std::vector<int>& label) {
  const int nf = static_cast<int>(label.size());
  std::vector<int> part(nf, -1);
  int used = 0;
  std::vector<int> stack;
  for (int f0 = 0; f0 < nf; ++f0) {
    if (part[f0] >= 0) continue;
    part[f0] = used;
    stack.push_back(f0);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int j = g.offsets[f]; j < g.offsets[f + 1]; ++j) {
        const int h = g.nbr[j];
        if (part[h] < 0 && label[h] == label[f]) part[h] = used, stack.push_back(h);
      }
    }
    ++used;
  }
  label = std::move(part);
  return used;
}

/// Number of ears of every chart: vertices where the chart has a single face (those that
/// remove_ears() leaves: its greedy moves do not always converge, and a mesh ear, a boundary
/// vertex with one face, cannot move at all).
std::vector<int> count_ears(const VertexFaces& vf, const std::vector<int>& label, int k) {
  std::vector<int> ears(k, 0);
  const int nv = static_cast<int>(vf.offsets.size()) - 1;
  for (int v = 0; v < nv; ++v)
    for (int i = vf.offsets[v]; i < vf.offsets[v + 1]; ++i) {
      const int l = label[vf.faces[i]];
      int same = 0;
      for (int j = vf.offsets[v]; j < vf.offsets[v + 1]; ++j) same += label[vf.faces[j]] == l;
      ears[l] += same == 1;
    }
  return ears;
}

/// Splits chart \p c in two: two far-apart seeds inside the chart (farthest point twice, plain
/// dual distance), grown against each other inside the chart; the second half gets label \p fresh.
void halve_chart(const DualGraph& g, std::vector<int>& label, int c, int fresh) {
  const int nf = static_cast<int>(label.size());
  int start = -1;
  for (int f = 0; f < nf && start < 0; ++f)
    if (label[f] == c) start = f;
  auto inside = [&](int, int j) { return label[g.nbr[j]] == c ? g.length[j] : kInf; };
  std::vector<double> dist;
  std::vector<int> from;
  auto farthest = [&] {
    int best = start;
    for (int f = 0; f < nf; ++f)
      if (dist[f] < kInf && dist[f] > dist[best]) best = f;
    return best;
  };
  grow(g, {start}, inside, dist, from);
  const int a = farthest();
  grow(g, {a}, inside, dist, from);
  const int b = farthest();
  if (a == b) return;
  grow(g, {a, b}, inside, dist, from);
  for (int f = 0; f < nf; ++f)
    if (from[f] == 1) label[f] = fresh;
}

/// Ear removal, then: a chart with more than four ears cannot have them all at the corners of its
/// square (Floater's one-to-one condition; the disk embedding falls back to the circle, L2 about
/// 2), so it is halved, until no chart has more than four ears (bounded rounds). Every
/// edge-connected part of a chart becomes a chart. Returns the number of charts.
int clean_charts(const TriMesh& mesh, const DualGraph& g, const VertexFaces& vf,
                 std::vector<int>& label) {
  int k = 0;
  for (int round = 0;; ++round) {
    remove_ears(mesh, vf, label);
    k = split_into_parts(g, label);
    if (round == 8) break;
    const std::vector<int> ears = count_ears(vf, label, k);
    int fresh = k;
    for (int c = 0; c < k; ++c)
      if (ears[c] > 4) halve_chart(g, label, c, fresh++);
    if (fresh == k) break;
  }
  return k;
}

}  // namespace

struct ChartSegmenter::Impl {
  const TriMesh& mesh;
  DualGraph g;
  VertexFaces vf;
  FarthestPoints seeds;
};

ChartSegmenter::ChartSegmenter(const TriMesh& mesh) {
  if (mesh.faces.empty()) throw InvalidInputError("segment_charts: the mesh has no faces");
  impl_ = std::make_unique<Impl>(Impl{mesh, build_dual_graph(mesh), build_vertex_faces(mesh), {}});
}

ChartSegmenter::~ChartSegmenter() = default;
ChartSegmenter::ChartSegmenter(ChartSegmenter&&) noexcept = default;
ChartSegmenter& ChartSegmenter::operator=(ChartSegmenter&&) noexcept = default;

std::vector<int> segment_charts(const TriMesh& mesh, const ChartSegmentOptions& options) {
  return ChartSegmenter(mesh).segment(options);
}

std::vector<int> ChartSegmenter::segment(const ChartSegmentOptions& options) {
  const TriMesh& mesh = impl_->mesh;
  const DualGraph& g = impl_->g;
  const int nf = mesh.num_faces();
  if (options.num_charts < 1 || options.lloyd_iterations < 0 || !(options.normal_weight >= 0) ||
      !std::isfinite(options.normal_weight))
    throw InvalidInputError("segment_charts: num_charts " + std::to_string(options.num_charts) +
                            ", lloyd_iterations " + std::to_string(options.lloyd_iterations) +
                            " or normal_weight out of range");
  std::vector<int> seeds = impl_->seeds.first(g, std::min(options.num_charts, nf));
  const int k = static_cast<int>(seeds.size());
  std::vector<Vec3> chart_normal(k);
  for (int c = 0; c < k; ++c) chart_normal[c] = g.normal[seeds[c]];
  std::vector<double> dist;
  std::vector<int> label;
  auto cost = [&](int c, int j) {
    const double dev = 1.0 - chart_normal[c].dot(g.normal[g.nbr[j]]);
    return g.length[j] * (1.0 + options.normal_weight * std::max(0.0, dev));
  };
  for (int it = 0;; ++it) {
    if (options.normal_weight == 0)  // the same costs (d * (1 + 0 * x) == d) without reading normals
      grow(g, seeds, [&](int, int j) { return g.length[j]; }, dist, label);
    else
      grow(g, seeds, cost, dist, label);
    if (it == options.lloyd_iterations) break;
    // Re-seed at the chart centres; the chart normal becomes the mean normal of the chart.
    std::vector<Vec3> sum(k, Vec3::Zero());
    for (int f = 0; f < nf; ++f)
      if (label[f] >= 0) sum[label[f]] += g.area[f] * g.normal[f];
    const std::vector<int> centre = chart_centres(g, label, k);
    for (int c = 0; c < k; ++c) {
      if (centre[c] >= 0) seeds[c] = centre[c];
      const double n = sum[c].norm();
      chart_normal[c] = n > 0 ? Vec3(sum[c] / n) : g.normal[seeds[c]];
    }
  }
  // Faces the growth cannot reach (only if the mesh is not connected) join chart 0.
  for (int& l : label)
    if (l < 0) l = 0;
  clean_charts(mesh, g, impl_->vf, label);
  return label;
}

std::vector<ChartMesh> extract_charts(const TriMesh& mesh, const std::vector<int>& face_chart,
                                      int num_charts) {
  const int nf = mesh.num_faces();
  if (static_cast<int>(face_chart.size()) != nf)
    throw InvalidInputError("extract_charts: " + std::to_string(face_chart.size()) +
                            " labels for " + std::to_string(nf) + " faces");
  for (int l : face_chart)
    if (l < 0 || l >= num_charts)
      throw InvalidInputError("extract_charts: chart label " + std::to_string(l) +
                              " outside [0, " + std::to_string(num_charts) + ")");
  // Corners glued across edges whose two faces are in the same chart are one chart vertex.
  const EdgeConnectivity ec = build_edges(mesh);
  std::vector<int> parent(3 * static_cast<size_t>(nf));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  auto corner_of = [&](int f, int v) {
    const Face& t = mesh.faces[f];
    return 3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  for (int e = 0; e < ec.num_edges(); ++e) {
    const auto& ef = ec.edge_faces[e];
    if (ef.size() != 2 || face_chart[ef[0]] != face_chart[ef[1]]) continue;
    for (int v : ec.edges[e]) {
      const int a = find(corner_of(ef[0], v)), b = find(corner_of(ef[1], v));
      if (a != b) parent[a] = b;
    }
  }
  std::vector<ChartMesh> charts(num_charts);
  std::vector<int> local(3 * static_cast<size_t>(nf), -1);
  for (int f = 0; f < nf; ++f) {
    ChartMesh& c = charts[face_chart[f]];
    Face t;
    for (int k = 0; k < 3; ++k) {
      const int r = find(3 * f + k);
      if (local[r] < 0) {
        local[r] = static_cast<int>(c.vertices.size());
        c.vertices.push_back(mesh.faces[f][k]);
        c.mesh.positions.push_back(mesh.positions[mesh.faces[f][k]]);
      }
      t[k] = local[r];
    }
    c.mesh.faces.push_back(t);
    c.faces.push_back(f);
  }
  return charts;
}

}  // namespace adaptex
