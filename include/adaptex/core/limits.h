#pragma once
/// \file limits.h
/// The documented resource caps of adaptex (docs/reliability.md). Every reader checks a size it is
/// about to allocate against these (and against the bytes left in the file) before allocating, so
/// that no input file can make adaptex exhaust memory or hang.
#include <cstdint>

namespace adaptex {

/// Largest input file (mesh, image, stroke file, project) read into memory: 1 GiB.
inline constexpr std::uint64_t kMaxInputFileBytes = std::uint64_t{1} << 30;

/// Largest number of elements (vertices, faces, list entries, accessor items) one mesh file may
/// declare: 100 million.
inline constexpr std::uint64_t kMaxMeshElements = 100'000'000;

/// Largest texture side in texels (the paint texture, `--size`, the studio's texture size, and the
/// side of any image read). An N x N painter keeps ~40 bytes per texel: 8192^2 is ~2.7 GB.
inline constexpr int kMaxTextureSize = 8192;

/// Largest image read (decal images, `reparam`'s texture): width x height <= 8192 x 8192 pixels,
/// checked from the PNG header before decoding.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t{kMaxTextureSize} * kMaxTextureSize;

}  // namespace adaptex
