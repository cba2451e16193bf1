// texel_fit_quality: what the least-squares texel fit gives, in surface PSNR (paint/asset_eval.h,
// 200k samples, seed 1) against the original texture (docs/texel_fit.md):
//  - on the artist's own layout at N²: box downsizing vs point sampling vs the fit;
//  - with --reparam, on the layout `adaptex reparam` makes (default options; --no-refine as the flag):
//    point sampling (resample_texture, today's reparam) vs the fit, at equal layout.
// Usage: texel_fit_quality [--sizes 256,128] [--reparam] [--no-refine] [--spt X] [--spst X]
//        [--smooth X] [--anchor X] [--tol X] [--write DIR] [--synthetic] [MESH.obj TEXTURE.png]...
// --synthetic adds the code-built 10k-face torus with a 1024² map (texel_fit_fixture.h).
#include <chrono>
#include <filesystem>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/texture_update.h"
#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/asset_eval.h"
#include "adaptex/paint/texel_fit.h"
#include "texel_fit_fixture.h"

using namespace adaptex;

namespace {

struct Args {
  std::vector<int> sizes{256, 128};
  std::string write_dir;  // --write DIR: the box-downsized and fitted textures as PNGs
  bool reparam = false, refine = true, synthetic = false;
  TexelFitOptions fit;
  std::vector<std::pair<std::string, std::string>> assets;
};

struct Asset {
  std::string name;
  TriMesh mesh;
  Parameterization param;
  ImageRGBA8 texture;
};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

Args parse(int argc, char** argv) {
  Args a;
  std::vector<std::string> pos;
  for (int k = 1; k < argc; ++k) {
    const std::string s = argv[k];
    auto value = [&]() -> std::string {
      if (k + 1 >= argc) throw InvalidInputError(s + " needs a value");
      return argv[++k];
    };
    if (s == "--sizes") {
      a.sizes.clear();
      std::stringstream ss(value());
      for (std::string tok; std::getline(ss, tok, ',');) a.sizes.push_back(std::stoi(tok));
    } else if (s == "--reparam") {
      a.reparam = true;
    } else if (s == "--no-refine") {
      a.refine = false;
    } else if (s == "--synthetic") {
      a.synthetic = true;
    } else if (s == "--spt") {
      a.fit.samples_per_texel = std::stod(value());
    } else if (s == "--spst") {
      a.fit.samples_per_source_texel = std::stod(value());
    } else if (s == "--write") {
      a.write_dir = value();
    } else if (s == "--anchor") {
      a.fit.anchor = std::stod(value());
    } else if (s == "--tol") {
      a.fit.tolerance = std::stod(value());
    } else if (s == "--smooth") {
      a.fit.smoothness = std::stod(value());
    } else {
      pos.push_back(s);
    }
  }
  if (pos.size() % 2) throw InvalidInputError("expected MESH TEXTURE pairs");
  for (size_t k = 0; k < pos.size(); k += 2) a.assets.emplace_back(pos[k], pos[k + 1]);
  return a;
}

double psnr(const Asset& in, const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& tex,
            const FaceData<int>& parent = {}) {
  return surface_psnr(in.mesh, in.param, in.texture, mesh, param, tex, parent).psnr;
}

/// Box vs point vs fit on the artist's layout.
void artist_layout(const Asset& a, const Args& args) {
  for (int N : args.sizes) {
    const double box = psnr(a, a.mesh, a.param, box_downsize(a.texture, N, N));
    const double point = psnr(a, a.mesh, a.param, resample_texture(a.param, a.texture, build_texel_map(a.mesh, a.param, N, N), 4));
    const auto t0 = std::chrono::steady_clock::now();
    const TexelFitResult r = fit_resize(a.mesh, a.param, a.texture, N, N, args.fit);
    const double time = seconds_since(t0);
    const double fit = psnr(a, a.mesh, a.param, r.texture);
    if (!args.write_dir.empty()) {
      const std::string stem = args.write_dir + "/" + std::filesystem::path(a.name).parent_path().parent_path().filename().string();
      write_png(stem + "_box" + std::to_string(N) + ".png", box_downsize(a.texture, N, N));
      write_png(stem + "_fit" + std::to_string(N) + ".png", r.texture);
    }
    std::printf("| %s | artist | %d | %.2f | %.2f | %.2f | **%+.2f** | %.0f ms, %lld samples, %d it |\n", a.name.c_str(), N,
                box, point, fit, fit - box, 1e3 * time, r.samples, r.iterations);
  }
}

/// Point sampling vs fit on the layout adaptex reparam makes (same adaptation as cmd_reparam.cpp).
void reparam_layout(const Asset& a, const Args& args) {
  AdaptOptions opt;
  opt.refine.enabled = args.refine;
  const TexelMap old_map = build_texel_map(a.mesh, a.param, a.texture.width, a.texture.height);
  const AdaptResult res = adapt_parameterization(a.mesh, a.param, a.texture, old_map, opt);
  const TriMesh& out_mesh = res.refined_mesh ? *res.refined_mesh : a.mesh;
  const Parameterization& old_layout = res.refined_mesh ? *res.refined_layout : a.param;
  const FaceData<int> parent = res.refined_mesh ? res.parent_face : FaceData<int>{};
  for (int N : args.sizes) {
    const ImageRGBA8 point = resample_texture(old_layout, a.texture, build_texel_map(out_mesh, res.param, N, N), 4);
    const auto t0 = std::chrono::steady_clock::now();
    const TexelFitResult r = fit_texels(out_mesh, old_layout, a.texture, res.param, N, N, args.fit);
    const double time = seconds_since(t0);
    const double p_point = psnr(a, out_mesh, res.param, point, parent), p_fit = psnr(a, out_mesh, res.param, r.texture, parent);
    std::printf("| %s | reparam%s (%d faces) | %d | %.2f | %.2f | **%+.2f** | %.0f ms, %d it |\n", a.name.c_str(),
                args.refine ? "" : " --no-refine", out_mesh.num_faces(), N, p_point, p_fit, p_fit - p_point, 1e3 * time,
                r.iterations);
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = parse(argc, argv);
    std::vector<Asset> assets;
    if (args.synthetic) {
      bench::TexturedFixture f = bench::textured_torus(100, 50, 1024);
      assets.push_back(Asset{"torus (code-built)", std::move(f.mesh), std::move(f.param), std::move(f.diffuse)});
    }
    for (const auto& [mesh, tex] : args.assets) {
      ReadOptions ro;
      ro.repair = true;  // real assets: split non-manifold edges (the surface and its UVs are unchanged)
      TexturedMesh tm = read_textured_obj(mesh, ro);
      assets.push_back(Asset{mesh, std::move(tm.mesh), std::move(tm.param), read_image(tex)});
    }
    std::printf("| asset | layout | size | box | point | fit | fit - box | fit time |\n|---|---|---|---|---|---|---|---|\n");
    for (const Asset& a : assets) artist_layout(a, args);
    if (args.reparam) {
      std::printf("\n| asset | layout | size | point | fit | fit - point | fit time |\n|---|---|---|---|---|---|---|\n");
      for (const Asset& a : assets) reparam_layout(a, args);
    }
  } catch (const std::exception& e) {
    std::cerr << "texel_fit_quality: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
