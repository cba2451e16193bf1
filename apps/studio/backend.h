#pragma once
/// \file backend.h
/// The one place where adaptex-studio calls the adaptex library (mesh reading, unwrapping, painting,
/// adaptive re-parameterization, stroke files, export, evaluation). The app and its tests use only
/// these functions, so a library change plugs in here without touching the app logic.
#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/progress.h"
#include "adaptex/paint/material_paint.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {
class Painter;
class PaintSession;
struct PaintSessionOptions;
}  // namespace adaptex

namespace adaptex::studio {

/// Reads a mesh file (adaptex::read_mesh), or a built-in shape named "builtin:sphere",
/// "builtin:torus", "builtin:trefoil", "builtin:plane", "builtin:icosphere".
/// \throw IoError, InvalidInputError, TopologyError (one-line messages naming the file)
TriMesh load_mesh(const std::string& path);

/// Initial parameterization (adaptex::unwrap) for a \p texture_size² texture with \p padding texels of
/// seam padding: adaptex::unwrap_options_for_texture(), as `adaptex paint --size N --padding P`.
/// \throw CancelledError when \p progress returns false
Parameterization unwrap_mesh(const TriMesh& mesh, int texture_size, int padding, const ProgressCallback& progress);

/// A model's own UV atlas with its base-colour texture (the artist's work the studio paints on).
struct ArtistAtlas {
  TriMesh mesh;            ///< As read_textured_asset() reads it (vertex order may differ from load_mesh()).
  Parameterization param;  ///< The artist's atlas (whole charts outside [0,1]^2 moved into it).
  ImageRGBA8 texture;      ///< The base-colour map (v = 0 first).
  std::string texture_path;
  double shared_fraction = 0;  ///< Covered texels that two or more UV triangles share (UvReport).
  int mirrored_charts = 0, degenerate_uv_faces = 0, straddling_charts = 0;
};

/// The atlas and base-colour texture of \p path (OBJ + MTL, glTF / GLB), or nullopt with the reason in
/// \p why (not such a file, no UVs, no base-colour texture, several of them, an unreadable map). Never
/// throws for the file's content: the caller then reads the mesh alone (load_mesh()), which reports a
/// corrupt mesh. \throw CancelledError never; std::bad_alloc only
std::optional<ArtistAtlas> read_artist_atlas(const std::string& path, std::string& why);

/// An artist's atlas adapted to the painting on it (adapt_artist_atlas()).
struct AtlasAdaptation {
  /// The new layout of the model's faces, or null: the artist's atlas is kept (the library's
  /// ranking found no layout better than it, nor than plain downsizing).
  std::shared_ptr<const Parameterization> param;
  std::shared_ptr<const ImageRGBA8> base;  ///< The artist's texture fitted onto *param (size²), else null.
  std::string chosen;        ///< The library's chosen candidate ("island_warp", "budget", "artist", ...).
  double psnr = 0;           ///< Surface PSNR of the chosen layout against the reference painting (dB).
  double psnr_before = 0;    ///< Same, the artist's atlas (the better of its fitted and downsized texels).
  int reference_size = 0;    ///< Side of the reference painting (texels).
  int flipped = 0;           ///< Faces of the new layout whose orientation differs from the atlas's.
  double shared_before = 0, shared_after = 0;  ///< Surface share whose texels other charts share too.
};

/// Adapts the artist's atlas \p atlas of \p mesh to its painting, keeping its charts, seams and shared
/// texels (adaptex::shrink_textured_mesh, docs/shrink.md): the reference is the painting at twice
/// \p size on the atlas (\p base, the artist's texture, bilinearly, then \p history's strokes); the
/// shrink fits it and \p base onto a \p size² layout. The strokes are not in the returned base: they
/// are replayed onto the new layout. The result is a function of its arguments (no state).
/// \pre atlas is a parameterization of mesh; 16 <= size <= kMaxTextureSize
/// \throw CancelledError when \p progress returns false; InvalidInputError bad input
AtlasAdaptation adapt_artist_atlas(const TriMesh& mesh, const Parameterization& atlas, const ImageRGBA8& base,
                                   const StrokeFile& history, int size, int padding, const ProgressCallback& progress);

/// A paintable texture on one parameterization (an adaptex::Painter, or the painter of the
/// PaintSession that produced an adapted parameterization).
class Canvas {
 public:
  /// \p padding: seam padding in texels (PaintSessionOptions::padding of the session).
  /// \pre mesh and param outlive the canvas and do not change
  /// \p base: the artist's texture the chart texels start from (sampled bilinearly at every texel
  /// centre: an exact copy at its own size), null: \p background.
  Canvas(const TriMesh& mesh, const Parameterization& param, int width, int height, const Vec3& background,
         int padding, const ImageRGBA8* base = nullptr);
  /// A copy of \p source (the painter of a session) on equal copies \p mesh, \p param of its mesh and
  /// parameterization: it paints on exactly as \p source would. \throw InvalidInputError they differ
  Canvas(const TriMesh& mesh, const Parameterization& param, const Painter& source);
  /// Takes over an adaptive painting session (its painter becomes this canvas).
  explicit Canvas(std::unique_ptr<PaintSession> session);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  void paint_stroke(const Stroke& stroke);
  void begin_stroke(const Stroke& style);
  /// \return touched texel rectangle (i0, j0, i1, j1), inclusive; empty if i1 < i0
  std::array<int, 4> add_dab(const Vec3& centre);
  void end_stroke();
  const ImageRGBA8& texture();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// What paint_history() produced: the painted mesh and parameterization with the history replayed
/// on them, the maps for the Inspect panel and the phase times for the status line.
struct SessionOutcome {
  std::shared_ptr<const TriMesh> mesh;  ///< The input mesh, or its refinement (same surface, more faces).
  /// With a refinement: per vertex of *mesh, the input's smooth normals interpolated at the vertex
  /// (a refined vertex lies inside an input face, whose own normal would shade it flat). Else empty.
  std::vector<Vec3> normals;
  std::shared_ptr<const Parameterization> param;
  std::unique_ptr<Canvas> canvas;       ///< The session's painter (references *mesh and *param).
  std::vector<std::pair<std::string, double>> phase_ms;
  ImageF importance, stretch, ls2, density;  ///< Whichever maps the method used (empty otherwise).
  GridWarp coarse, fine;                ///< Two-stage: both; single / density-flow: fine only.
  bool adapted = false;   ///< A re-parameterization ran (mode != None).
  bool accepted = true;   ///< false: the "never worse" safeguard kept the initial layout.
  double damping = 1;
};

/// Paints \p history on \p initial and re-parameterizes once: exactly `adaptex paint --reparam end`
/// (an adaptex::PaintSession with \p options, schedule End, texture update Replay). With
/// options.adapt.mode None the history is only painted.
/// \pre initial is a parameterization of *mesh
/// \throw CancelledError when \p progress returns false; InvalidInputError bad options
SessionOutcome paint_history(const std::shared_ptr<const TriMesh>& mesh, const Parameterization& initial,
                             const StrokeFile& history, const PaintSessionOptions& options,
                             const ProgressCallback& progress);

/// An adaptex::PaintSession on the schedule `adaptex paint --reparam each-stroke` uses (replay, the
/// surface cache, the min-gain gate), kept across strokes by the studio's live adaptation
/// (live_adaptation.h): a cycle costs the same after 10 strokes as after 1,000, where
/// paint_history() replays the whole history. Not thread-safe: one thread drives it.
class LiveSession {
 public:
  /// \p progress: AdaptOptions::progress of the session's cycles (false cancels one: CancelledError).
  /// \pre initial is a parameterization of *mesh
  /// \throw InvalidInputError bad options
  LiveSession(std::shared_ptr<const TriMesh> mesh, const Parameterization& initial, const PaintSessionOptions& options,
              const Vec3& background, const ProgressCallback& progress);
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  /// Paints \p strokes and runs one each-stroke cycle for them (PaintSession::add_strokes).
  /// \throw CancelledError (strokes recorded, layout unchanged, not settled); InvalidInputError a bad stroke
  void add(const std::vector<Stroke>& strokes);
  /// Ends on end mode's layout and texture for the strokes so far (PaintSession::finish; a no-op when
  /// settled()). \throw CancelledError (the session stays usable and unsettled)
  void settle();
  bool settled() const;
  size_t strokes() const;  ///< Strokes painted so far.
  /// The layout differs from the last snapshot()'s (or the session settled since): worth showing.
  bool changed() const;
  /// The session's layout, maps and texture, with a canvas of its own (the session keeps painting).
  /// \p alongside (optional) runs on another thread with the outcome's mesh while the canvas is built
  /// (the caller's picking structure); its exception is rethrown.
  SessionOutcome snapshot(const std::function<void(const TriMesh&)>& alongside = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// What paint_material_history() produced: the layout and the material's textures on it.
struct MaterialOutcome {
  std::shared_ptr<const TriMesh> mesh;  ///< The input mesh, or its refinement (same surface, more faces).
  std::shared_ptr<const Parameterization> param;
  std::shared_ptr<const MaterialTextures> textures;
  /// With a refinement: per vertex of *mesh, the input's smooth normals (as SessionOutcome::normals).
  std::vector<Vec3> normals;
  bool adapted = false;  ///< The adapted layout was kept (false: \p initial).
  std::vector<std::pair<std::string, double>> phase_ms;
};

/// Paints the layered material \p file on \p initial and adapts the layout once to its summed error
/// model: exactly what `adaptex paint MESH --strokes FILE.json` does for a version 2 file
/// (adaptex::adapt_material with options.texture_size, options.padding and options.adapt). A layered
/// material adapts with density-flow or none: another method paints on \p initial (none).
/// \pre initial is a parameterization of *mesh
/// \throw CancelledError when \p progress returns false; InvalidInputError bad input
MaterialOutcome paint_material_history(const std::shared_ptr<const TriMesh>& mesh, const Parameterization& initial,
                                       const MaterialStrokeFile& file, const PaintSessionOptions& options,
                                       const ProgressCallback& progress);
/// An adaptex::MaterialPaintSession (each-stroke adaptation of a layered material: per-layer point
/// caches, the min-gain gate) kept across strokes by the studio's live material adaptation
/// (live_material.h): a stroke costs an incremental composite and one gated cycle, where
/// paint_material_history() composites and adapts the whole document. Not thread-safe.
class MaterialLiveSession {
 public:
  /// \p file: the document so far (its strokes are painted now). \p options: texture size, padding and
  /// method (density-flow adapts, any other paints on \p initial, as paint_material_history()).
  /// \p progress: the cycles' AdaptOptions::progress (false cancels one: CancelledError).
  /// \pre initial is a parameterization of *mesh. \throw InvalidInputError bad options or file
  MaterialLiveSession(std::shared_ptr<const TriMesh> mesh, const Parameterization& initial, MaterialStrokeFile file,
                      const PaintSessionOptions& options, const ProgressCallback& progress);
  ~MaterialLiveSession();
  MaterialLiveSession(const MaterialLiveSession&) = delete;
  MaterialLiveSession& operator=(const MaterialLiveSession&) = delete;

  /// Appends \p strokes to layer \p layer (its mask when \p mask), then one gated cycle
  /// (MaterialPaintSession::add_strokes; a mask: one cycle per stroke, add_stroke()).
  /// \throw CancelledError (strokes recorded, layout unchanged); InvalidInputError a bad stroke or layer
  void add(int layer, const std::vector<MaterialStroke>& strokes, bool mask);
  const MaterialStrokeFile& history() const;
  /// The held layout and its textures (a copy); mesh, param and normals are shared with the last
  /// snapshot while the layout has not changed (the renderer then keeps its geometry).
  MaterialOutcome snapshot();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes the material as `adaptex paint` does: DIR/NAME.obj/.mtl/.png and the roughness, metallic,
/// normal and height maps, atomically. \throw OutputError, InvalidInputError a bad name
void export_material_obj(const std::filesystem::path& dir, const std::string& name, const TriMesh& mesh,
                         const Parameterization& param, const MaterialTextures& textures);
/// Writes the material's glTF metallic-roughness .glb (the bytes `adaptex paint` writes), atomically.
/// \throw OutputError
void export_material_glb(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization& param,
                         const MaterialTextures& textures);

/// PSNR (dB) of \p texture on \p param against the exact signal of \p history (adaptex eval).
double texture_psnr(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                    const StrokeFile& history, long long samples = 200000);

/// Reads a stroke file (strict, adaptex::read_strokes). \throw IoError, InvalidInputError
StrokeFile load_strokes(const std::filesystem::path& path);
/// Reads a stroke file of version 1 or 2 (adaptex::read_any_strokes). \throw IoError, InvalidInputError
AnyStrokeFile load_any_strokes(const std::filesystem::path& path);
/// Writes a stroke file atomically (adaptex::write_strokes). \throw OutputError
void save_strokes(const std::filesystem::path& path, const StrokeFile& file);
/// Writes OBJ + MTL + PNG into \p dir as NAME.obj/.mtl/.png, atomically. \throw OutputError
void export_obj(const std::filesystem::path& dir, const std::string& name, const TriMesh& mesh,
                const Parameterization& param, const ImageRGBA8& texture);
/// Writes a binary glTF with the texture embedded, atomically; its sampler clamps, or repeats when
/// a UV lies outside [0,1]^2 (an artist's atlas with charts across its border). \throw OutputError
void export_glb(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization& param,
                const ImageRGBA8& texture);
/// Writes a PNG atomically. \throw OutputError
void save_png(const std::filesystem::path& path, const ImageRGBA8& img);
/// Reads an image (decals). \throw IoError
ImageRGBA8 load_image(const std::filesystem::path& path);

}  // namespace adaptex::studio
