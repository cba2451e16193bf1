#pragma once
/// \file named_mesh.h
/// Meshes the study and benchmark programs accept by name besides files: the shapes built in code
/// (core/shapes.h), so that a study runs on topologies the shared meshes do not have and where
/// ../shared is absent.
///   genusG           genus_surface(G), 0 <= G <= 64      (closed genus-G sculpture-like surface)
///   holesK           sphere_with_holes(K), 0 <= K <= 1000
///   sphereSxT        sphere(S, T), 3 <= S, T <= 4096     (or sphereS,T where arguments are not comma lists)
///   torusAxB         torus(A, B), 3 <= A, B <= 4096      (or torusA,B)
///   pinched          genus_surface(3) with a pinched hole
///   pinched_annulus  pinched_annulus(8)
///   tiny200          tiny_components(200)
///   1M               torus(2000, 250)
#include <optional>
#include <stdexcept>
#include <string>

#include "adaptex/core/mesh.h"
#include "adaptex/core/shapes.h"

namespace adaptex::bench {

/// A parsed code-built mesh name: the shape and its numbers.
struct CodeBuiltName {
  std::string shape;  ///< genus, holes, sphere, torus, or a fixed name (pinched, pinched_annulus, tiny200, 1M)
  int a = 0, b = 0;
};

namespace detail {
/// The decimal number \p text in [lo, hi]. \throw std::invalid_argument naming \p name otherwise
inline int bounded_number(const std::string& name, const std::string& text, int lo, int hi) {
  const bool digits = !text.empty() && text.size() <= 9 && text.find_first_not_of("0123456789") == std::string::npos;
  const int v = digits ? std::stoi(text) : -1;
  if (!digits || v < lo || v > hi)
    throw std::invalid_argument(name + ": expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                "] after the shape's name, got '" + text + "'");
  return v;
}
}  // namespace detail

/// \p name parsed, or std::nullopt when it starts with none of the shape names above (then it is a
/// file name). \throw std::invalid_argument a shape name with missing, malformed or out-of-range numbers
inline std::optional<CodeBuiltName> parse_code_built_name(const std::string& name) {
  for (const char* fixed : {"pinched", "pinched_annulus", "tiny200", "1M"})
    if (name == fixed) return CodeBuiltName{name};
  auto starts = [&name](const std::string& p) { return name.rfind(p, 0) == 0; };
  if (starts("genus")) return CodeBuiltName{"genus", detail::bounded_number(name, name.substr(5), 0, 64)};
  if (starts("holes")) return CodeBuiltName{"holes", detail::bounded_number(name, name.substr(5), 0, 1000)};
  for (const char* shape : {"sphere", "torus"}) {
    const std::string s = shape;
    if (!starts(s)) continue;
    const std::string rest = name.substr(s.size());
    const size_t sep = rest.find_first_of(",x");
    if (sep == std::string::npos) throw std::invalid_argument(name + ": expected " + s + "AxB, e.g. " + s + "96x40");
    return CodeBuiltName{s, detail::bounded_number(name, rest.substr(0, sep), 3, 4096),
                         detail::bounded_number(name, rest.substr(sep + 1), 3, 4096)};
  }
  return std::nullopt;
}

/// The mesh of a parsed name.
inline TriMesh build_code_built_mesh(const CodeBuiltName& n) {
  if (n.shape == "genus") return shapes::genus_surface(n.a);
  if (n.shape == "holes") return shapes::sphere_with_holes(n.a);
  if (n.shape == "sphere") return shapes::sphere(n.a, n.b);
  if (n.shape == "torus") return shapes::torus(n.a, n.b);
  if (n.shape == "pinched") return shapes::with_pinched_hole(shapes::genus_surface(3));
  if (n.shape == "pinched_annulus") return shapes::pinched_annulus(8);
  if (n.shape == "tiny200") return shapes::tiny_components(200);
  return shapes::torus(2000, 250);  // "1M"
}

/// The code-built mesh named \p name, or std::nullopt when \p name is not one of the names above.
/// \throw std::invalid_argument as parse_code_built_name()
inline std::optional<TriMesh> code_built_mesh(const std::string& name) {
  const std::optional<CodeBuiltName> n = parse_code_built_name(name);
  if (!n) return std::nullopt;
  return build_code_built_mesh(*n);
}

}  // namespace adaptex::bench
