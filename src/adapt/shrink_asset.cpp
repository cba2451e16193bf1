/// \file shrink_asset.cpp
/// shrink_textured_asset(): material groups -> each group's faces as their own mesh -> shrink -> one layout.
#include "adaptex/adapt/shrink_asset.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/union_find.h"

namespace adaptex {

namespace {

/// Charts of \p param: faces connected through shared wedges, numbered in order of their first face.
std::vector<int> wedge_charts(const Parameterization& param, int* count) {
  UnionFind wedges(param.num_wedges());
  for (const Face& t : param.uv_faces)
    for (int k = 1; k < 3; ++k) wedges.unite(t[0], t[k]);
  std::vector<int> id(param.num_wedges(), -1), chart(param.uv_faces.size());
  int n = 0;
  for (size_t f = 0; f < param.uv_faces.size(); ++f) {
    int& c = id[wedges.find(param.uv_faces[f][0])];
    if (c < 0) c = n++;
    chart[f] = c;
  }
  *count = n;
  return chart;
}

/// A group's faces as a mesh and layout of their own (vertices and wedges in input order).
struct SubAsset {
  TriMesh mesh;
  Parameterization param;
};

SubAsset extract_faces(const TexturedAsset& a, const std::vector<int>& faces) {
  SubAsset s;
  std::vector<int> vmap(a.mesh.positions.size(), -1), wmap(a.param.uv.size(), -1);
  for (int f : faces)
    for (int k = 0; k < 3; ++k) vmap[a.mesh.faces[f][k]] = wmap[a.param.uv_faces[f][k]] = 0;
  for (size_t v = 0; v < vmap.size(); ++v)
    if (vmap[v] == 0) {
      vmap[v] = s.mesh.num_vertices();
      s.mesh.positions.push_back(a.mesh.positions[v]);
    }
  for (size_t w = 0; w < wmap.size(); ++w)
    if (wmap[w] == 0) {
      wmap[w] = s.param.num_wedges();
      s.param.uv.push_back(a.param.uv[w]);
    }
  s.param.wedge_vertex.assign(s.param.uv.size(), 0);
  for (int f : faces) {
    Face m, u;
    for (int k = 0; k < 3; ++k) {
      m[k] = vmap[a.mesh.faces[f][k]];
      u[k] = wmap[a.param.uv_faces[f][k]];
      s.param.wedge_vertex[u[k]] = m[k];
    }
    s.mesh.faces.push_back(m);
    s.param.uv_faces.push_back(u);
  }
  s.param.face_chart = wedge_charts(s.param, &s.param.num_charts);
  return s;
}

/// The group's maps for shrink_textured_mesh(): each image file once, base colour maps first.
std::vector<ShrinkMap> group_maps(const TexturedAsset& a, const MaterialGroupShrink& g) {
  std::vector<ShrinkMap> maps(g.slots.size());
  for (const GroupMapRef& r : g.refs) {
    ShrinkMap& m = maps[r.map];
    if (!m.image.empty()) continue;
    m.slot = g.slots[r.map];
    m.kind = map_kind_of_slot(m.slot);
    m.image = a.materials[r.material].find(r.slot)->image;
    if (m.image.empty())
      throw InvalidInputError(a.materials[r.material].find(r.slot)->origin + ": the map was not loaded");
  }
  return maps;
}

std::string group_name(const TexturedAsset& a, const MaterialGroupShrink& g) {
  std::string s;
  for (int m : g.materials) s += (s.empty() ? "" : "+") + a.materials[m].name;
  return s;
}

/// The whole mesh's layout: each group's result on its faces, the input's UVs on the other faces.
Parameterization assemble_layout(const TexturedAsset& a, const std::vector<MaterialGroupShrink>& groups) {
  Parameterization out;
  out.uv_faces.resize(a.mesh.faces.size());
  out.face_chart.assign(a.mesh.faces.size(), -1);
  std::vector<char> done(a.mesh.faces.size(), 0);
  for (const MaterialGroupShrink& g : groups) {
    const Parameterization& p = g.result.param;
    const int w0 = out.num_wedges();
    out.uv.insert(out.uv.end(), p.uv.begin(), p.uv.end());
    for (size_t i = 0; i < g.faces.size(); ++i) {
      const int f = g.faces[i];
      for (int k = 0; k < 3; ++k) out.uv_faces[f][k] = w0 + p.uv_faces[i][k];
      out.face_chart[f] = out.num_charts + (i < p.face_chart.size() ? p.face_chart[i] : 0);
      done[f] = 1;
    }
    out.num_charts += std::max(p.num_charts, 1);
  }
  std::map<int, int> wedge, chart;  // the other faces: their input wedges and charts, once each
  for (size_t f = 0; f < a.mesh.faces.size(); ++f) {
    if (done[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const int w = a.param.uv_faces[f][k];
      auto it = wedge.try_emplace(w, out.num_wedges()).first;
      if (it->second == out.num_wedges()) out.uv.push_back(a.param.uv[w]);
      out.uv_faces[f][k] = it->second;
    }
    const int c = f < a.param.face_chart.size() ? a.param.face_chart[f] : 0;
    auto it = chart.try_emplace(c, out.num_charts).first;
    if (it->second == out.num_charts) ++out.num_charts;
    out.face_chart[f] = it->second;
  }
  out.wedge_vertex.assign(out.uv.size(), 0);
  for (size_t f = 0; f < a.mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) out.wedge_vertex[out.uv_faces[f][k]] = a.mesh.faces[f][k];
  return out;
}

double mean_psnr(const std::vector<MaterialGroupShrink>& groups, bool downsized) {
  double area = 0, mse = 0;
  for (const MaterialGroupShrink& g : groups) area += g.area;
  for (const MaterialGroupShrink& g : groups) {
    const double w = area > 0 ? g.area / area : 1.0 / groups.size();
    mse += w * std::pow(10.0, -(downsized ? g.result.psnr_downsized : g.result.psnr) / 10.0);
  }
  return mse > 0 ? -10.0 * std::log10(mse) : 200.0;
}

}  // namespace

int shrink_output_size(const AssetShrinkOptions& o, const ImageRGBA8& first) {
  if (o.size > 0) return o.size;
  const double side = std::max(first.width, first.height) / std::sqrt(o.factor);
  return std::clamp(static_cast<int>(std::lround(side)), 8, kMaxTextureSize);
}

std::vector<MaterialGroupShrink> material_groups(const TexturedAsset& asset) {
  const int M = static_cast<int>(asset.materials.size());
  UnionFind shared(M);
  std::map<std::string, int> image_owner;
  for (int m = 0; m < M; ++m)
    for (const TextureMap& t : asset.materials[m].maps) {
      const auto [it, fresh] = image_owner.try_emplace(t.path.lexically_normal().string(), m);
      if (!fresh) shared.unite(m, it->second);
    }
  std::vector<MaterialGroupShrink> groups;
  std::vector<int> group_of_root(M, -1);
  for (int m = 0; m < M; ++m) {
    if (asset.materials[m].maps.empty()) continue;
    int& g = group_of_root[shared.find(m)];
    if (g < 0) {
      g = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[g].materials.push_back(m);
  }
  // Each image file is one map of its group, base colour maps first (the first map leads the shrink).
  for (MaterialGroupShrink& g : groups) {
    std::map<std::string, int> index;
    for (bool base : {true, false})
      for (int m : g.materials)
        for (const TextureMap& t : asset.materials[m].maps) {
          if ((t.slot == MapSlot::BaseColor) != base) continue;
          const auto [it, fresh] = index.try_emplace(t.path.lexically_normal().string(), static_cast<int>(g.slots.size()));
          if (fresh) g.slots.push_back(map_slot_name(t.slot));
          g.refs.push_back({m, t.slot, it->second});
        }
  }
  return groups;
}

int wrap_charts_into_unit_square(Parameterization& param, double tolerance, const std::string& what) {
  int n = 0;
  const std::vector<int> chart = wedge_charts(param, &n);
  std::vector<Vec2> lo(n, Vec2::Constant(HUGE_VAL)), hi(n, Vec2::Constant(-HUGE_VAL));
  std::vector<int> first(n, -1), wedge_chart(param.uv.size(), -1);
  for (size_t f = 0; f < chart.size(); ++f) {
    const int c = chart[f];
    if (first[c] < 0) first[c] = static_cast<int>(f);
    for (int w : param.uv_faces[f]) {
      lo[c] = lo[c].cwiseMin(param.uv[w]);
      hi[c] = hi[c].cwiseMax(param.uv[w]);
      wedge_chart[w] = c;
    }
  }
  std::vector<Vec2> shift(n, Vec2::Zero());
  int moved = 0;
  for (int c = 0; c < n; ++c) {
    const Vec2 extent = hi[c] - lo[c];
    if (extent.x() > 1 + tolerance || extent.y() > 1 + tolerance)
      throw InvalidInputError(what + ": the UV chart of face " + std::to_string(first[c]) + " spans u " +
                              std::to_string(lo[c].x()) + " to " + std::to_string(hi[c].x()) + ", v " +
                              std::to_string(lo[c].y()) + " to " + std::to_string(hi[c].y()) +
                              ": more than one texture tile (a tiling texture), which shrink does not support");
    shift[c] = -(0.5 * (lo[c] + hi[c])).array().floor().matrix();
    if (shift[c] != Vec2::Zero()) ++moved;
  }
  for (size_t w = 0; w < param.uv.size(); ++w)
    if (wedge_chart[w] >= 0) param.uv[w] += shift[wedge_chart[w]];
  return moved;
}

AssetShrinkResult shrink_textured_asset(const TexturedAsset& asset, const AssetShrinkOptions& options) {
  if (options.size <= 0 && !(options.factor >= 1)) throw InvalidInputError("shrink: give a size or a factor >= 1");
  AssetShrinkResult r;
  std::vector<MaterialGroupShrink> groups = material_groups(asset);
  std::vector<int> group_of(asset.materials.size(), -1);
  for (size_t g = 0; g < groups.size(); ++g)
    for (int m : groups[g].materials) group_of[m] = static_cast<int>(g);
  const auto material_of = [&](int f) {
    const int m = f < static_cast<int>(asset.face_material.size()) ? asset.face_material[f] : -1;
    return m >= 0 && m < static_cast<int>(group_of.size()) ? m : -1;
  };
  // One textured material and no other in use: faces without a material are its faces too (an OBJ
  // without `usemtl`), as the one-material shrink has always taken them.
  bool only_one = groups.size() == 1 && groups[0].materials.size() == 1;
  for (int f = 0; f < asset.mesh.num_faces() && only_one; ++f)
    only_one = material_of(f) < 0 || material_of(f) == groups[0].materials[0];
  for (int f = 0; f < asset.mesh.num_faces(); ++f) {
    const int m = material_of(f);
    if (only_one || (m >= 0 && group_of[m] >= 0)) groups[only_one ? 0 : group_of[m]].faces.push_back(f);
  }
  // A textured material without faces has nothing to shrink.
  for (MaterialGroupShrink& g : groups)
    if (!g.faces.empty()) r.groups.push_back(std::move(g));
  if (r.groups.empty()) throw InvalidInputError("no face has a material with a texture map");
  // One group on every face: the asset itself, so that the result is the one-material shrink's exactly.
  const bool whole = r.groups.size() == 1 && static_cast<int>(r.groups[0].faces.size()) == asset.mesh.num_faces();
  for (size_t k = 0; k < r.groups.size(); ++k) {
    MaterialGroupShrink& g = r.groups[k];
    const std::string name = group_name(asset, g);
    SubAsset sub = whole ? SubAsset{asset.mesh, asset.param} : extract_faces(asset, g.faces);
    g.wrapped_charts = wrap_charts_into_unit_square(sub.param, options.uv_tolerance, "material '" + name + "'");
    const std::vector<ShrinkMap> maps = group_maps(asset, g);
    ShrinkOptions so = options.shrink;
    so.size = g.size = shrink_output_size(options, maps[0].image);
    so.progress = options.progress;
    if (r.groups.size() > 1 && options.progress) {
      const std::string prefix = name + " (" + std::to_string(k + 1) + "/" + std::to_string(r.groups.size()) + "): ";
      so.progress = [prefix, cb = options.progress](std::string_view phase, double t) {
        return cb(prefix + std::string(phase), t);
      };
    }
    for (int f : g.faces) g.area += face_area(asset.mesh, f);
    g.result = shrink_textured_mesh(sub.mesh, sub.param, maps, so);
  }
  r.param = whole ? r.groups[0].result.param : assemble_layout(asset, r.groups);
  r.psnr = r.groups.size() == 1 ? r.groups[0].result.psnr : mean_psnr(r.groups, false);
  r.psnr_downsized = r.groups.size() == 1 ? r.groups[0].result.psnr_downsized : mean_psnr(r.groups, true);
  return r;
}

}  // namespace adaptex
