#pragma once
/// \file shapes.h
/// Meshes built in code, for tests, benchmarks and the demo (no data files needed).
#include "adaptex/core/mesh.h"

namespace adaptex::shapes {

/// Flat square [0,size]^2 in the z = 0 plane, n x n quads split into 2n^2 triangles. Disk.
TriMesh plane(int n, double size = 1.0);
/// UV sphere of radius r: closed, genus 0. \pre slices >= 3, stacks >= 2.
TriMesh sphere(int slices, int stacks, double r = 1.0);
/// Icosphere with \p subdivisions levels of 4:1 subdivision (20 * 4^s faces). Closed, genus 0.
TriMesh icosphere(int subdivisions, double r = 1.0);
/// Torus with major radius R and minor radius r: closed, genus 1.
TriMesh torus(int major_segments, int minor_segments, double R = 1.0, double r = 0.35);
/// Closed genus-2 surface (a smooth "double torus"), built as an implicit surface by marching tetrahedra.
/// \p resolution is the number of grid cells along the longest axis.
TriMesh double_torus(int resolution = 48);
/// Open cylinder (tube) of radius r and height h: 2 boundary loops, genus 0.
TriMesh open_cylinder(int segments, int rings, double r = 0.5, double h = 1.0);
/// Disk (annular grid) with \p holes circular holes: 1 + holes boundary loops, genus 0.
TriMesh disk_with_holes(int holes, int resolution = 32);
/// Two disjoint shapes (a sphere and a torus) in one mesh: 2 components.
TriMesh two_components();
/// Three triangles sharing one edge (a non-manifold "fan"): one non-manifold edge.
TriMesh nonmanifold_fan();
/// Two tetrahedra touching at a single vertex: one non-manifold vertex.
TriMesh bowtie_vertex();
/// A closed genus-1 trefoil-knot tube: the demo's embedded default mesh.
TriMesh trefoil_knot(int segments = 240, int sides = 24, double tube = 0.28);

}  // namespace adaptex::shapes
