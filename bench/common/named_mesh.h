#pragma once
/// \file named_mesh.h
/// Meshes the study and benchmark programs accept by name besides files: the shapes built in code
/// (core/shapes.h), so that a study runs on topologies the shared meshes do not have and where
/// ../shared is absent.
///   genusG           genus_surface(G)           (closed genus-G sculpture-like surface)
///   holesK           sphere_with_holes(K)
///   sphereSxT        sphere(S, T)     (or sphereS,T where the argument list is not comma-separated)
///   torusAxB         torus(A, B)      (or torusA,B)
///   pinched          genus_surface(3) with a pinched hole
///   pinched_annulus  pinched_annulus(8)
///   tiny200          tiny_components(200)
///   1M               torus(2000, 250)
#include <optional>
#include <string>

#include "adaptex/core/mesh.h"
#include "adaptex/core/shapes.h"

namespace adaptex::bench {

/// The code-built mesh named \p name, or std::nullopt when \p name is not one of the names above.
/// \throw std::invalid_argument or std::out_of_range on a malformed number (e.g. "genusx")
inline std::optional<TriMesh> code_built_mesh(const std::string& name) {
  auto number_after = [&name](size_t prefix) { return std::stoi(name.substr(prefix)); };
  auto pair_after = [&name](size_t prefix) {
    const size_t comma = name.find_first_of(",x", prefix);
    if (comma == std::string::npos) throw std::invalid_argument(name + ": expected two numbers AxB");
    return std::pair<int, int>(std::stoi(name.substr(prefix, comma - prefix)), std::stoi(name.substr(comma + 1)));
  };
  if (name.rfind("genus", 0) == 0) return shapes::genus_surface(number_after(5));
  if (name.rfind("holes", 0) == 0) return shapes::sphere_with_holes(number_after(5));
  if (name.rfind("sphere", 0) == 0) {
    const auto [s, t] = pair_after(6);
    return shapes::sphere(s, t);
  }
  if (name.rfind("torus", 0) == 0) {
    const auto [a, b] = pair_after(5);
    return shapes::torus(a, b);
  }
  if (name == "pinched") return shapes::with_pinched_hole(shapes::genus_surface(3));
  if (name == "pinched_annulus") return shapes::pinched_annulus(8);
  if (name == "tiny200") return shapes::tiny_components(200);
  if (name == "1M") return shapes::torus(2000, 250);
  return std::nullopt;
}

}  // namespace adaptex::bench
