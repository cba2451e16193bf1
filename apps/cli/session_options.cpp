// Option strings of `adaptex paint` -> PaintSessionOptions.
#include "session_options.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "adaptex/adapt/method.h"
#include "adaptex/core/enum_names.h"
#include "adaptex/core/errors.h"

namespace adaptex::cli {

std::vector<int> parse_grid(const std::string& text) {
  std::vector<int> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    // Digits only: std::stoi alone would also take " 16" and "+16".
    const bool digits = !item.empty() && item.size() <= 4 &&
                        std::all_of(item.begin(), item.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
    const int v = digits ? std::stoi(item) : 0;
    if (v < 2 || v > kMaxGridCells)
      throw InvalidInputError("--grid: '" + text + "' must be one or two comma-separated integers in [2, " +
                              std::to_string(kMaxGridCells) + "] (e.g. 16,256)");
    out.push_back(v);
  }
  if (out.empty() || out.size() > 2 || text.back() == ',')
    throw InvalidInputError("--grid: '" + text + "' must be one or two comma-separated integers (e.g. 16,256)");
  if (out.size() == 2 && out[0] > out[1])
    throw InvalidInputError("--grid: '" + text + "': the coarse grid must not be finer than the fine one (e.g. 16,256)");
  return out;
}

void set_grid(AdaptOptions& o, const std::vector<int>& grid) {
  if (grid.size() > 2) throw InvalidInputError("--grid: give FINE or COARSE,FINE (e.g. 16,256)");
  for (int g : grid)
    if (g < 1 || g > kMaxGridCells)
      throw InvalidInputError("--grid: sizes must be in [1, " + std::to_string(kMaxGridCells) + "], got " +
                              std::to_string(g));
  if (!grid.empty()) o.thesis.fine_grid = grid.back();
  if (grid.size() == 2) o.thesis.coarse_grid = grid.front();
}

ReparamSchedule parse_reparam_schedule(const std::string& name) {
  return parse_enum<ReparamSchedule>(name, "reparam schedule");
}

TextureUpdate parse_texture_update(const std::string& name) { return parse_enum<TextureUpdate>(name, "texture update"); }

std::vector<std::string> adapt_method_names(bool with_none) {
  std::vector<std::string> out;
  for (const AdaptMethodInfo* m : adapt_methods())
    if (with_none || m->make) out.push_back(m->name);
  return out;
}

std::string adapt_methods_help(bool with_none) {
  std::string out;
  for (const AdaptMethodInfo* m : adapt_methods())
    if (with_none || m->make) out += (out.empty() ? "" : " | ") + m->name + " (" + m->description + ")";
  return out;
}

PaintSessionOptions make_session_options(int size, int padding, const std::string& mode,
                                         const std::vector<int>& grid, double alpha, double beta,
                                         const std::string& reparam, const std::string& update,
                                         const std::filesystem::path& debug_maps) {
  PaintSessionOptions o;
  o.texture_size = size;
  o.padding = padding;
  o.adapt.mode = parse_adapt_mode(mode);
  set_grid(o.adapt, grid);
  if (alpha >= 0) o.adapt.thesis.alpha = alpha;
  if (beta >= 0) o.adapt.thesis.beta = beta;
  if (!std::isfinite(alpha) || !std::isfinite(beta)) throw InvalidInputError("--alpha/--beta must be finite");
  o.schedule = parse_reparam_schedule(reparam);
  o.update = parse_texture_update(update);
  o.debug_dir = debug_maps;
  return o;
}

}  // namespace adaptex::cli
