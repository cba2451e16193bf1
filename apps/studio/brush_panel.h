#pragma once
/// \file brush_panel.h
/// Panels of the studio's brush for a layered material (Dear ImGui): a layer's mask and fill, and the
/// pen-pressure curves. Drawn by StudioUi (ui.cpp); every change goes through the App.
#include <functional>
#include <string>

#include "app.h"

namespace adaptex::studio {

/// Prints where the last widget is under a name (StudioUi::trace, for the GUI tests).
using TraceWidget = std::function<void(const char*)>;

/// A plain-words tooltip for the last widget.
void tooltip(const char* text);

/// The active layer's mask (add / remove, paint on it with a value) and fills of the layer or its mask.
void mask_panel(App& app, const TraceWidget& trace);

/// The brush's pressure curves for radius and opacity: three control points each (pressure 0, 0.5, 1).
void pressure_panel(BrushSettings& brush, const TraceWidget& trace);

/// "Stamp the decal image": a click stamps the loaded decal image at the cursor (BrushSettings::stamp).
void stamp_option(App& app, const TraceWidget& trace);

/// Save / load a brush preset at the path in \p path (edited in place; empty: `brush.json` in the
/// last folder used), or through a file dialog (\p choose: FileKind::LoadBrushPreset / SaveBrushPreset).
void preset_panel(App& app, std::string& path, const TraceWidget& trace,
                  const std::function<void(FileKind)>& choose);

}  // namespace adaptex::studio
