// `adaptex eval MESH.obj TEXTURE.png STROKES.json [--samples K] [--seed S]`: MSE and PSNR of a
// texture against the exact stroke signal (paint/eval.h; contract: shared/docs/strokes.md), printed
// as one JSON object on stdout. Bad input: exit 2 with one line on stderr (main.cpp).
#include <nlohmann/json.hpp>

#include <chrono>
#include <iostream>

#include "adaptex/adapt/report_json.h"
#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/strokes.h"
#include "cli_common.h"

namespace adaptex::cli {

namespace {

struct EvalArgs {
  std::string mesh, texture, strokes;
  long long samples = EvalOptions{}.samples;
  std::uint64_t seed = EvalOptions{}.seed;
};

void run_eval(const EvalArgs& a, const Context& ctx) {
  if (a.samples < 1) throw InvalidInputError("eval: --samples must be >= 1 (got " + std::to_string(a.samples) + ")");
  const auto t0 = std::chrono::steady_clock::now();
  const StrokeFile strokes = read_strokes(a.strokes);
  for (const auto& w : strokes.warnings) ctx.warn(w);
  const TexturedMesh tm = read_textured_obj(a.mesh);
  const ImageRGBA8 texture = read_image(a.texture);
  EvalOptions opt;
  opt.samples = a.samples;
  opt.seed = a.seed;
  const EvalResult r = evaluate_texture(tm.mesh, tm.param, texture, strokes, opt);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json j;
  const nlohmann::ordered_json result = eval_result_json(r);
  for (const auto& [key, value] : result.items()) j[key] = nlohmann::json(value);
  j["texture"] = {texture.width, texture.height};
  j["strokes"] = strokes.strokes.size();
  j["dabs"] = strokes.num_dabs();
  j["seconds"] = secs;
  std::cout << j.dump() << "\n";
}

}  // namespace

void add_eval_command(CLI::App& app, Context& ctx) {
  auto args = std::make_shared<EvalArgs>();
  auto* sub = app.add_subcommand(
      "eval",
      "MSE/PSNR of a texture against the exact painted signal of a stroke file, over K points spread "
      "uniformly by surface area (bilinear reconstruction, clamp-to-edge, v = 0 bottom). Prints JSON "
      "{mse, psnr, samples, seed, texture, strokes, dabs, seconds}.");
  sub->add_option("mesh", args->mesh, "Textured OBJ (vt + f v/vt) whose UVs the texture uses")->required();
  sub->add_option("texture", args->texture, "The texture image (PNG; OBJ convention, v = 0 bottom row)")->required();
  sub->add_option("strokes", args->strokes, "Stroke file (adaptex.strokes v1)")->required();
  sub->add_option("--samples", args->samples, "Number K of surface samples (default 1000000)");
  sub->add_option("--seed", args->seed, "Seed of the sample positions (default 1)");
  sub->callback([args, &ctx] { run_eval(*args, ctx); });
}

}  // namespace adaptex::cli
