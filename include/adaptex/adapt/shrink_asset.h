#pragma once
/// \file shrink_asset.h
/// The shrink of a whole textured asset: every textured material (or group of materials sharing an
/// image file) is shrunk on its own faces by shrink_textured_mesh(); untextured faces keep their UVs
/// (docs/shrink.md, "Several materials").
#include <string>
#include <vector>

#include "adaptex/adapt/shrink.h"
#include "adaptex/io/asset_io.h"

namespace adaptex {

/// Settings of shrink_textured_asset().
struct AssetShrinkOptions {
  /// Settings of every group's shrink; shrink.size and shrink.progress are set per group (below).
  ShrinkOptions shrink;
  int size = 0;       ///< Output size of every group's maps (0: from factor).
  double factor = 0;  ///< Or: K× fewer texels than each group's base colour map (each side / √K).
  /// How far (UV units) a chart may exceed one tile's width or height (default 1e-3, as AssetReadOptions).
  double uv_tolerance = 1e-3;
  /// Phases "NAME (k/n): PHASE" of group k of n, fractions as the group's shrink reports them.
  ProgressCallback progress;
};

/// One map of a group: the input map and the output map (index into MaterialGroupShrink::result.maps).
struct GroupMapRef {
  int material = -1;  ///< Index into TexturedAsset::materials.
  MapSlot slot = MapSlot::BaseColor;
  int map = -1;       ///< Index into the group's maps (result.maps).
};

/// Materials shrunk together (one material, or materials that share an image file) and their result.
struct MaterialGroupShrink {
  std::vector<int> materials;        ///< Indices into TexturedAsset::materials, ascending.
  std::vector<int> faces;            ///< The group's faces (input indices, ascending).
  std::vector<GroupMapRef> refs;     ///< Every map of every material of the group.
  std::vector<std::string> slots;    ///< Name of each of result.maps (the slot that first uses it).
  double area = 0;                   ///< 3-D area of the group's faces.
  int size = 0;                      ///< Output width = height of the group's maps.
  int wrapped_charts = 0;            ///< Charts moved by an integer tile offset into [0,1]² first.
  ShrinkResult result;               ///< On the group's faces (result.param: the group's sub-layout).
};

/// Result of shrink_textured_asset().
struct AssetShrinkResult {
  /// The output layout of the whole mesh: each group's faces get their group's layout, other faces keep
  /// their input UVs. With one group covering every face it is that group's result.param exactly.
  Parameterization param;
  std::vector<MaterialGroupShrink> groups;  ///< In the order of their first material.
  /// Overall surface PSNR of the base colour (first map) of every group, result and plain downsizing:
  /// the MSE of each group weighted by its share of the textured faces' 3-D area (as the measure's
  /// area-uniform samples would weight it), in dB.
  double psnr = 0, psnr_downsized = 0;
};

/// The output size of a group whose first map is \p first: options.size, or each side of \p first / √factor
/// (rounded, within [8, kMaxTextureSize]).
int shrink_output_size(const AssetShrinkOptions& options, const ImageRGBA8& first);

/// The groups of materials that shrink_textured_asset() shrinks together: materials with a texture
/// map, joined when they name the same image file (TextureMap::path). Faces are not filled in.
std::vector<MaterialGroupShrink> material_groups(const TexturedAsset& asset);

/// Moves every chart of \p param (faces connected through shared wedges) by the integer offset that
/// brings the centre of its UV bounding box into [0,1)²: a chart inside one tile then lies in [0,1]²
/// (the same texels under repeat wrapping, and now under clamp-to-edge too); a chart that crosses a
/// tile border keeps crossing it (its part outside reads the edge texels, as the shrink's measure reads
/// the original). Returns the number of charts moved.
/// \throw InvalidInputError a chart is wider or taller than one tile by more than \p tolerance (a
/// tiling texture): no clamped image can hold it; the message names \p what and a face of the chart.
int wrap_charts_into_unit_square(Parameterization& param, double tolerance, const std::string& what);

/// Shrinks every textured material of \p asset (groups of material_groups()) on its own faces; with
/// one textured material and no other in use, faces without a material are shrunk with it.
/// \pre asset as read_textured_asset() gives it, its maps loaded
/// \throw InvalidInputError no textured material, a material's map is empty, a chart wider than a
/// UV tile, bad options (as shrink_textured_mesh())
/// \throw CancelledError options.progress returned false
AssetShrinkResult shrink_textured_asset(const TexturedAsset& asset, const AssetShrinkOptions& options);

}  // namespace adaptex
