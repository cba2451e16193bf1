#pragma once
/// \file shapes.h
/// Meshes built in code, for tests, benchmarks and the demo (no data files needed).
#include <vector>

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

/// Closed surface of genus \p genus: a row of \p genus tori (major radius 1, minor 0.4, centres
/// 2.1 apart) joined by a smooth union and polygonized by marching tetrahedra; genus 0 is an
/// icosphere of about as many faces as one torus. \p cells_per_unit grid cells per unit length
/// (double_torus(48) uses about 9); about 110 cells_per_unit^2 faces per torus (1.8k at the
/// default 4). \pre 0 <= genus <= 64, 2 <= cells_per_unit <= 200.
/// \throw InvalidInputError genus or cells_per_unit out of range
TriMesh genus_surface(int genus, int cells_per_unit = 4);
/// Unit sphere (icosphere with \p subdivisions levels) with \p holes circular holes, centred on a
/// Fibonacci spiral of points, each of angular radius 0.3 sqrt(4 pi / holes) (at most 0.6 rad):
/// genus 0, \p holes boundary loops, no pinched vertex (a vertex whose removed neighbours form
/// several fans is removed too). \pre holes >= 1 and the holes are at least two edges wide
/// (holes <= 4^subdivisions). \throw InvalidInputError out of range
TriMesh sphere_with_holes(int holes, int subdivisions = 5);

/// Disjoint union of \p meshes in one mesh (vertices and faces appended in order, indices shifted).
/// \pre every mesh has valid indices \throw nothing beyond std::bad_alloc
TriMesh disjoint_union(const std::vector<TriMesh>& meshes);
/// Square annulus whose inner and outer boundaries touch at one *pinched* vertex: the ring of
/// cells of width one around an n x n grid on [0,1]^2 (z = 0), with its corner cell at (1, 1)
/// removed, so that the two cells next to the inner corner (1 - 1/n, 1 - 1/n) meet only at that
/// vertex. Split there (core/pinched.h) it is a disk: genus 0, one boundary loop of 8n - 8 edges.
/// \pre n >= 3 \throw InvalidInputError n < 3
TriMesh pinched_annulus(int n = 8);
/// \p closed with a hole whose boundary touches itself: two non-adjacent faces of the one-ring of
/// a vertex v (the first vertex of valence >= 4) are removed, so v keeps two separate fans (a
/// pinched vertex) and the hole is one loop of 6 edges through v twice. Split at v, the surface
/// keeps the genus of \p closed and has one boundary loop.
/// \pre \p closed is a closed, manifold, consistently oriented mesh
/// \throw InvalidInputError no vertex of valence >= 4 with a closed one-ring
TriMesh with_pinched_hole(const TriMesh& closed);

/// \p count tiny components, the hard cases of a range scan for a solver: component i has
/// 1 + i % 10 faces; with at least 3 faces and i even it is a closed fan around one interior vertex
/// (with i % 4 == 0 and 4 faces the centre lies exactly on a rim edge: one zero-area face; with
/// 5 faces two rim vertices are duplicate points: one zero-area face with a zero-length edge),
/// otherwise a triangle strip whose last triangle is a sliver (height 1e-6 of its base) when
/// i % 3 == 2. Every fifth component is moved so that its first vertex has the position of the
/// previous component's first vertex (duplicate points across components). Each component is a
/// manifold disk, consistently oriented. \pre count >= 1 \throw InvalidInputError count < 1
TriMesh tiny_components(int count);
/// A synthetic range scan of about \p target_faces faces in \p components components (the first
/// holds about half the faces, the next ones share the rest, and every tenth is a tiny one of 1-10
/// faces): noisy height fields over grids, with isolated single-face holes (extra boundary loops),
/// and \p zero_area_faces / 2 interior grid edges collapsed onto one endpoint (its two faces get zero
/// area, its two vertices become duplicate points; the faces stay manifold). Deterministic in \p seed.
/// \pre target_faces >= 100 * components, components >= 1, zero_area_faces >= 0
/// \throw InvalidInputError out of range
TriMesh synthetic_scan(int target_faces, int components, int zero_area_faces, unsigned seed = 1);

}  // namespace adaptex::shapes
