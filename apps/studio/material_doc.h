#pragma once
/// \file material_doc.h
/// The studio's layered material document: a stroke file of version 2 (the library's
/// MaterialStrokeFile, docs/strokes.md) edited by layer operations and strokes, with unlimited undo /
/// redo. The document is a fold of an edit log over the file it was opened with: undo moves the last
/// edit to the redo stack and folds the log again (no snapshots: memory stays linear in the strokes).
#include <cstdint>
#include <string>
#include <vector>

#include "adaptex/paint/material_strokes.h"

namespace adaptex::studio {

/// One undoable edit of a MaterialDocument.
struct MaterialEdit {
  enum class Kind { AddLayer, DeleteLayer, MoveLayer, Visible, Opacity, Blend, Rename, Stroke, AddMask, RemoveMask,
                    MaskStroke };
  Kind kind = Kind::Stroke;
  int layer = 0;       ///< The layer edited (AddLayer: the index the new layer gets).
  int target = 0;      ///< MoveLayer: the index the layer moves to.
  bool flag = false;   ///< Visible.
  double value = 0;    ///< Opacity; AddMask: the mask's start value.
  BlendMode blend = BlendMode::Normal;
  std::string name;    ///< AddLayer, Rename.
  MaterialStroke stroke;  ///< Stroke / MaskStroke: appended to the layer's (mask's) strokes.
};

class MaterialDocument {
 public:
  /// A document of \p file (at least one layer: an empty file gets one, "Layer 1"); nothing to undo.
  explicit MaterialDocument(MaterialStrokeFile file = {});

  const MaterialStrokeFile& file() const { return file_; }
  int num_layers() const { return int(file_.layers.size()); }
  /// The layer strokes are painted on (the UI's selection; not an edit).
  int active() const { return active_; }
  void set_active(int layer);

  /// Edits (each undoable). \throw InvalidInputError an index out of range, a value out of [0,1],
  /// deleting the only layer, a stroke breaking the stroke-file contract.
  void add_layer(const std::string& name);  ///< Above the active layer; it becomes the active one.
  void delete_layer(int layer);
  void move_layer(int layer, int to);       ///< Reorders (index 0 is the lowest layer).
  void set_visible(int layer, bool visible);
  /// \p merge: a drag continuing the last edit of this layer's opacity replaces it (one undo step).
  void set_opacity(int layer, double opacity, bool merge = false);
  void set_blend(int layer, BlendMode blend);
  void rename(int layer, const std::string& name);
  /// Appends \p stroke to the active layer.
  void add_stroke(MaterialStroke stroke);
  /// Gives \p layer a mask of start value \p value (none yet), or removes its mask (with its strokes).
  void add_mask(int layer, double value);
  void remove_mask(int layer);
  /// Appends \p stroke (brush, fill or erase; mask_value painted) to the active layer's mask.
  /// \throw InvalidInputError the layer has no mask, or the stroke breaks the contract
  void add_mask_stroke(MaterialStroke stroke);

  bool undo();
  bool redo();
  bool can_undo() const { return !log_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  /// Incremented by every change (edits, undo, redo).
  std::uint64_t version() const { return version_; }
  /// Brush, erase and fill strokes over all layers (not their masks).
  size_t num_strokes() const;
  /// A name no layer has yet: "Layer N".
  std::string next_layer_name() const;

 private:
  void apply(const MaterialEdit& e);
  void push(MaterialEdit e);
  void check_layer(int layer, const char* what) const;

  MaterialStrokeFile base_, file_;
  std::vector<MaterialEdit> log_, redo_;
  int active_ = 0;
  std::uint64_t version_ = 0;
};

}  // namespace adaptex::studio
