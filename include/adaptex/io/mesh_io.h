#pragma once
/// \file mesh_io.h
/// Reading meshes (OBJ, OFF/COFF, PLY incl. tristrips, STL ascii/binary, glTF/GLB) with validation,
/// and writing OBJ with UVs. Readers are well-kept libraries (tinyobjloader, assimp, tinygltf).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// Options of read_mesh().
struct ReadOptions {
  /// Split non-manifold edges and drop duplicate faces instead of rejecting the mesh (pinched
  /// vertices, where only separate fans of faces meet, are always split).
  bool repair = false;
};

/// What read_mesh() changed or noticed. Every non-zero count also produced a warning line.
struct ReadReport {
  std::string format;                 ///< Detected format ("obj", "off", "ply", "stl", "gltf", "glb").
  int dropped_degenerate_faces = 0;   ///< Zero-area faces removed.
  int dropped_unreferenced_vertices = 0;  ///< Vertices used by no face, removed.
  int dropped_duplicate_faces = 0;    ///< Faces with the same vertex set as an earlier one (repair).
  int split_nonmanifold_vertices = 0; ///< Vertices duplicated to make the mesh manifold (repair).
  /// Pinched vertices (several separate fans of faces at one vertex) split into one vertex per fan,
  /// always (no repair needed); the copies keep the exact position.
  int split_pinched_vertices = 0;
  /// Faces reversed because their winding disagreed with the majority of their surface (always;
  /// core/orientation.h). Positions are untouched.
  int flipped_faces = 0;
  int welded_vertices = 0;            ///< Vertices merged because the format split them.
  std::vector<std::string> warnings;  ///< Human-readable warning lines (file name included).
};

/// Reads and validates a triangle mesh (polygons are fan-triangulated). Pinched vertices are split
/// (core/pinched.h) and a mixed face winding is made consistent (core/orientation.h), each with a
/// warning; nothing else about the faces changes.
/// Positions keep the file's units and values; vertex order follows the file where the format has
/// shared vertices. Vertices split by the format (STL, OBJ with separate v/vn/vt indices, assimp's
/// per-corner output) are welded by identical position.
/// \throw IoError unreadable, corrupt or truncated file, unknown format
/// \throw InvalidInputError no faces, NaN/inf coordinates, indices out of range
/// \throw TopologyError non-manifold edges or duplicate faces (unless options.repair)
TriMesh read_mesh(const std::filesystem::path& path, const ReadOptions& options = {},
                  ReadReport* report = nullptr);

/// read_mesh() on bytes already in memory: everything read_mesh() does after reading the file (the
/// same format reader, validation and repair), so a file and its bytes give the same mesh or the same
/// error. For callers that hold the bytes (the fuzz targets, tests, network or archive input).
/// \p format is the extension that selects the reader ("obj", ".OFF", "glb", ...; case-insensitive).
/// \p name is the file the bytes stand for: messages name it, and its folder resolves a .gltf's
/// external buffers (which must be regular files there, as for read_mesh()).
/// \pre none (every problem is reported by an exception).
/// \throw IoError unknown format, \p bytes empty or larger than kMaxInputFileBytes, corrupt or truncated
/// \throw InvalidInputError, TopologyError as read_mesh()
TriMesh read_mesh_from_memory(const std::string& bytes, const std::string& format, const std::filesystem::path& name,
                              const ReadOptions& options = {}, ReadReport* report = nullptr);

/// Validates an in-memory mesh the same way read_mesh() does (degenerate/unreferenced are dropped,
/// pinched vertices are split, the rest throws); \p name is used in messages in place of a file name.
/// \throw InvalidInputError, TopologyError as read_mesh()
TriMesh validate_mesh(TriMesh mesh, const std::string& name, const ReadOptions& options = {},
                      ReadReport* report = nullptr);

/// Signed volume enclosed by the faces (divergence theorem, origin-independent only for closed
/// meshes): positive when the faces are wound counter-clockwise seen from outside, negative when
/// clockwise (e.g. the shared horse.ply and bunny.ply). Nothing is ever flipped by the readers.
double signed_volume(const TriMesh& mesh);

/// A mesh with its UV layout, as stored in an OBJ with `vt` and `f v/vt`.
struct TexturedMesh {
  TriMesh mesh;
  Parameterization param;
};

/// Reads an OBJ with texture coordinates (`mtllib` material files are not opened). Charts are the connected components of the UV faces
/// (faces sharing a wedge). Wedges are the distinct (vertex, vt) pairs, ordered by vt index, so that
/// for the usual file (every vt used with one vertex) wedge w is the file's vt number w+1.
/// Validation as read_mesh() (degenerate faces / unreferenced vertices dropped, the UV faces with them).
/// \throw IoError, InvalidInputError (as read_mesh; also a face without vt, a vt index out of range or a
/// non-finite vt)
TexturedMesh read_textured_obj(const std::filesystem::path& path, const ReadOptions& options = {},
                               ReadReport* report = nullptr);

/// Writes `v` (input positions, full precision), `vt` and `f v/vt` (1-based). If \p mtllib is set,
/// writes `mtllib` + `usemtl` lines referring to it. Writes to \p path directly: wrap with
/// AtomicOutput for all-or-nothing behaviour. \throw OutputError
void write_obj(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization* param,
               const std::optional<std::string>& mtllib = std::nullopt,
               const std::string& material = "adaptex_paint");

/// write_obj() of a mesh with several materials: face f uses materials[face_material[f]], a `usemtl`
/// starts every run of faces of one material, faces keep their order.
/// \pre face_material.size() == F, every entry a valid index into materials
/// \throw InvalidInputError inconsistent input; OutputError
void write_obj(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization& param,
               const std::string& mtllib, const std::vector<std::string>& materials,
               const std::vector<int>& face_material);

}  // namespace adaptex
