#pragma once
/// \file test_scene.h
/// The fixture of the paint and adapt tests: a torus built in code (shapes.h), its unwrap() layout
/// and a generated stroke set on it. Header-only; the test links adaptex::adaptex (param + paint).
#include <cstdint>

#include "adaptex/core/parameterization.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/param/unwrap.h"

namespace adaptex::test {

/// A mesh, its layout and a stroke history on it.
struct Scene {
  TriMesh mesh;
  Parameterization param;  ///< unwrap(mesh).param
  StrokeFile strokes;      ///< generate_strokes(mesh, {kind, seed, count})
};

/// shapes::torus(major, minor), unwrap()'s layout of it and \p count strokes of \p kind drawn from \p seed.
inline Scene torus_scene(int major, int minor, StrokeKind kind, int count, std::uint64_t seed = GenerateOptions{}.seed) {
  Scene sc;
  sc.mesh = shapes::torus(major, minor);
  sc.param = unwrap(sc.mesh).param;
  GenerateOptions go;
  go.kind = kind;
  go.count = count;
  go.seed = seed;
  sc.strokes = generate_strokes(sc.mesh, go);
  return sc;
}

}  // namespace adaptex::test
