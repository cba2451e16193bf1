/// \file ui.cpp
/// Dear ImGui panels (see ui.h).
#include "ui.h"

#include "brush_panel.h"

#include <imgui.h>
#include <imgui_internal.h>  // the popup stack: Esc closes the menus and popups above any modal
#include <imgui_stdlib.h>

#include <algorithm>
#include <functional>
#include <iostream>
#include <vector>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/method.h"
#include <cmath>

#include "adaptex/paint/export.h"
#include "native_dialog.h"

namespace adaptex::studio {
namespace {

void draw_line(ImageRGBA8& img, double x0, double y0, double x1, double y1, std::array<uint8_t, 3> c) {
  const int n = int(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
  for (int k = 0; k <= n; ++k) {
    const double t = double(k) / n;
    const int i = int(x0 + (x1 - x0) * t), j = int(y0 + (y1 - y0) * t);
    if (i < 0 || j < 0 || i >= img.width || j >= img.height) continue;
    uint8_t* p = img.texel(i, j);
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
  }
}

/// Blue -> cyan -> yellow -> red heat colour of t in [0,1] (clamped), 8-bit RGB.
std::array<uint8_t, 3> heat_rgb(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const double r = std::clamp(2.0 * t - 0.5, 0.0, 1.0), g = std::clamp(t < 0.5 ? 2 * t : 2 - 2 * t + 0.3, 0.0, 1.0),
               b = std::clamp(1.0 - 2.0 * t, 0.0, 1.0);
  return {uint8_t(255 * r), uint8_t(255 * g), uint8_t(255 * b)};
}

/// Heat map of a [0,1] map (values clamped).
ImageRGBA8 heat_image(const ImageF& m) {
  ImageRGBA8 img(m.width, m.height, {0, 0, 0, 255});
  for (int j = 0; j < m.height; ++j)
    for (int i = 0; i < m.width; ++i) {
      const auto c = heat_rgb(m.at(i, j));
      std::copy(c.begin(), c.end(), img.texel(i, j));
    }
  return img;
}

/// A colour bar of heat_rgb from \p low to \p high (the words at its ends), full width.
void heat_bar(const char* low, const char* high) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float w = std::max(64.f, ImGui::GetContentRegionAvail().x), h = ImGui::GetFontSize() * 0.8f;
  constexpr int kSteps = 32;
  for (int k = 0; k < kSteps; ++k) {
    const auto c = heat_rgb((k + 0.5) / kSteps);
    dl->AddRectFilled(ImVec2(p.x + w * k / kSteps, p.y), ImVec2(p.x + w * (k + 1) / kSteps, p.y + h),
                      IM_COL32(c[0], c[1], c[2], 255));
  }
  ImGui::Dummy(ImVec2(w, h));
  ImGui::TextUnformatted(low);
  ImGui::SameLine(std::max(0.f, w - ImGui::CalcTextSize(high).x));
  ImGui::TextUnformatted(high);
}

/// Largest value of a map (0 for an empty one).
float max_value(const ImageF& m) {
  float mx = 0;
  for (float v : m.data) mx = std::max(mx, v);
  return mx;
}


/// Opens (once) and begins the modal pop-up \p title, centred; says so on stdout the frame it appears
/// (scripted tests wait for the line). \return ImGui::BeginPopupModal's answer (EndPopup when true)
bool begin_modal(const char* title, App& app) {
  if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  ImGui::SetNextWindowPos(ImVec2(app.camera().width * 0.5f, app.camera().height * 0.5f), ImGuiCond_Appearing,
                          ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings))
    return false;
  if (ImGui::IsWindowAppearing()) std::cout << "adaptex-studio: dialog: " << title << std::endl;
  return true;
}

bool escape_pressed() { return ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false); }

/// Esc closes the menus and (non-modal) pop-ups above the top-most modal; modals answer Esc themselves.
void close_popups_on_escape() {
  if (!escape_pressed()) return;
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  int keep = g.OpenPopupStack.Size;
  while (keep > 0) {
    const ImGuiWindow* w = g.OpenPopupStack[keep - 1].Window;
    if (w && (w->Flags & ImGuiWindowFlags_Modal)) break;
    --keep;
  }
  if (keep < g.OpenPopupStack.Size) ImGui::ClosePopupToLevel(keep, true);
}

/// "12 s", "5 min", "3 h", "2 days".
std::string age_text(double seconds) {
  char buf[32];
  if (seconds < 90) std::snprintf(buf, sizeof buf, "%.0f s", std::max(0.0, seconds));
  else if (seconds < 5400) std::snprintf(buf, sizeof buf, "%.0f min", seconds / 60);
  else if (seconds < 129600) std::snprintf(buf, sizeof buf, "%.0f h", seconds / 3600);
  else std::snprintf(buf, sizeof buf, "%.0f days", seconds / 86400);
  return buf;
}

/// \p m divided by its largest value (density maps have mean 1 and no fixed upper bound).
ImageF scaled_to_max(const ImageF& m) {
  ImageF out = m;
  const float mx = max_value(m);
  if (mx > 0)
    for (float& v : out.data) v /= mx;
  return out;
}

/// \p text, shortened with "..." (whole UTF-8 characters) to fit \p width pixels.
std::string fit_text(const std::string& text, float width) {
  if (ImGui::CalcTextSize(text.c_str()).x <= width) return text;
  std::string s = text;
  while (!s.empty() && ImGui::CalcTextSize((s + "...").c_str()).x > width) {
    unsigned char last = 0;
    do {
      last = static_cast<unsigned char>(s.back());
      s.pop_back();
    } while (!s.empty() && (last & 0xC0) == 0x80);
  }
  return s + "...";
}

}  // namespace

void StudioUi::draw(App& app) {
  overlay_.draw(app);  // over the 3-D view, under the panels; also with the panels hidden
  collect_messages(app);
  if (const auto answer = native_.poll(); answer && !answer->empty()) act(app, native_.request().kind, *answer);
  // Every ordinary window first, the one modal last: a window that appears after a modal opened in
  // the same frame trips Dear ImGui 1.86's assertion `blocking_modal != NULL` (its bug #4920).
  if (app.view().show_ui) {
    const float menu_h = menu_bar(app);
    side_panel(app, menu_h);
    material_window(app, menu_h);
    if (show_inspect_) inspect_window(app, menu_h);
    if (app.view().show_help) help_window(app);
    if (app.take_open_dialog_request()) choose(app, FileKind::OpenMesh);
    status_bar(app);
    if (!toast_text_.empty() && ImGui::GetTime() < toast_until_) toast(app);
  }
  working_window(app);
  modal(app);
  close_popups_on_escape();
}

StudioUi::Modal StudioUi::which_modal(const App& app) const {
  if (app.confirm()) return Modal::Confirm;  // also the follow-up of Recover with unsaved strokes
  if (app.recovery_offer()) return Modal::Recovery;
  if (native_.is_open()) return Modal::Native;
  if (browser_) return Modal::Browser;
  if (!error_text_.empty()) return Modal::Error;
  return Modal::None;
}

void StudioUi::modal(App& app) {
  const Modal m = which_modal(app);
  if (m == Modal::None && !open_modal_.empty()) {  // answered elsewhere (a key, the App): close it
    if (ImGui::BeginPopupModal(open_modal_.c_str(), nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::CloseCurrentPopup();
      ImGui::EndPopup();
    }
  }
  open_modal_.clear();
  switch (m) {
    case Modal::Confirm: confirm_prompt(app); break;
    case Modal::Recovery: recovery_prompt(app); break;
    case Modal::Native: native_wait(app); break;
    case Modal::Browser: browser_window(app); break;
    case Modal::Error: error_prompt(app); break;
    case Modal::None: break;
  }
}

float StudioUi::menu_bar(App& app) {
  if (!ImGui::BeginMainMenuBar()) return 0;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New")) app.request_new();
    if (ImGui::MenuItem("Open mesh...", "Ctrl+O")) choose(app, FileKind::OpenMesh);
    if (ImGui::BeginMenu("Open recent", !app.recent_files().empty())) {
      for (const auto& r : app.recent_files())
        if (ImGui::MenuItem(r.c_str())) act(app, FileKind::OpenMesh, r);
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Open project...")) choose(app, FileKind::OpenProject);
    if (ImGui::MenuItem("Fresh unwrap", nullptr, app.unwrap())) app.set_unwrap(!app.unwrap());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("On: models are unwrapped afresh (the layout adapts to the paint).\n"
                        "Off: a model with its own UV atlas and base-colour texture is painted on them.\n"
                        "Changing it reopens the model, keeping the strokes.");
    if (ImGui::MenuItem("Save", "Ctrl+S")) save(app);
    if (ImGui::MenuItem("Save As...")) choose(app, FileKind::SaveProject);
    if (ImGui::MenuItem("Export OBJ...")) choose(app, FileKind::ExportObjFolder);
    if (ImGui::MenuItem("Export GLB...")) choose(app, FileKind::ExportGlb);
    if (ImGui::MenuItem("Screenshot...")) choose(app, FileKind::Screenshot);
    if (ImGui::MenuItem("Load decal (stencil)...")) choose(app, FileKind::LoadImage);
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) app.request_quit();
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    if (ImGui::MenuItem("Undo", "Ctrl+Z", false, app.can_undo())) app.undo();
    if (ImGui::MenuItem("Redo", "Ctrl+Shift+Z", false, app.can_redo())) app.redo();
    ImGui::Separator();
    if (ImGui::MenuItem("Brush", "B", app.brush().tool == Tool::Brush)) app.brush().tool = Tool::Brush;
    if (ImGui::MenuItem("Eraser", "E", app.brush().tool == Tool::Eraser)) app.brush().tool = Tool::Eraser;
    if (ImGui::MenuItem("Eyedropper", "I", app.brush().tool == Tool::Eyedropper)) app.brush().tool = Tool::Eyedropper;
    if (ImGui::MenuItem("Smaller brush", "[")) scale_brush(app.brush(), 1 / 1.15);
    if (ImGui::MenuItem("Larger brush", "]")) scale_brush(app.brush(), 1.15);
    if (ImGui::MenuItem("Project stencil", "P", false, app.stencil().has_value())) app.project_decal(app.decal_opacity());
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Frame the model", "Home")) app.frame_model();
    ImGui::MenuItem("Wireframe", "W", &app.view().wireframe);
    ImGui::MenuItem("Texel-density checker", "C", &app.view().checker);
    ImGui::MenuItem("Lit material preview", "V", &app.view().pbr);
    if (ImGui::MenuItem("Fixed layout", "L", app.view().fixed_layout)) app.toggle_fixed_layout();
    ImGui::MenuItem("Inspect panel", nullptr, &show_inspect_);
    ImGui::MenuItem("Layers and channels", nullptr, &show_material_);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    ImGui::MenuItem("Shortcuts", "F1", &app.view().show_help);
    ImGui::EndMenu();
  }
  const float h = ImGui::GetWindowSize().y;
  ImGui::EndMainMenuBar();
  return h;
}

void StudioUi::side_panel(App& app, float top) {
  // Left of the view, from the menu bar to the status line; its right edge can be dragged.
  const float bottom = ImGui::GetFrameHeight() + 8, h = std::max(100.f, float(app.camera().height) - top - bottom);
  const float w = std::clamp(float(app.camera().width) * 0.3f, kMinPanelWidth, kPanelWidth);
  ImGui::SetNextWindowPos(ImVec2(0, top), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(w, h), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(kMinPanelWidth, h),
                                      ImVec2(std::max(kPanelWidth, float(app.camera().width) * 0.6f), h));
  ImGui::Begin("adaptex studio", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoTitleBar);
  // Widgets leave room for the longest label on their right: labels never clip.
  ImGui::PushItemWidth(-ImGui::CalcTextSize("Decal opacity ").x);
  if (ImGui::CollapsingHeader("File", ImGuiTreeNodeFlags_DefaultOpen)) file_panel(app);
  if (ImGui::CollapsingHeader("Brush", ImGuiTreeNodeFlags_DefaultOpen)) brush_panel(app);
  if (ImGui::CollapsingHeader("View")) view_panel(app);
  if (ImGui::CollapsingHeader("Adapt", ImGuiTreeNodeFlags_DefaultOpen)) adapt_panel(app);
  ImGui::Checkbox("Inspect panel", &show_inspect_);
  ImGui::PopItemWidth();
  ImGui::End();
}

void StudioUi::choose(App& app, FileKind kind) {
  if (native_.is_open() || browser_) return;  // one dialog at a time
  const FileRequest r = file_request(kind);
  // Save dialogs propose a file name (<mesh stem>.adaptex / .glb / .png) in the last folder used.
  const std::filesystem::path suggested = app.suggested_path(kind);
  const bool named = r.save && suggested.has_filename();
  const std::string folder = (named ? suggested.parent_path() : suggested).string();
  const std::string name = named ? suggested.filename().string() : std::string();
  if (native_dialogs_available()) return native_.open(r, folder, name);
  browser_ = r;  // the in-app browser (browser_window)
  browser_ready_ = false;
  browser_dir_ = folder;
  browser_name_ = name;
}

void StudioUi::act(App& app, FileKind kind, const std::string& path) {
  switch (kind) {
    case FileKind::OpenMesh: open_path_ = path, app.request_open_mesh(path); break;
    case FileKind::OpenProject: project_path_ = path, app.request_open_project(path); break;
    case FileKind::SaveProject: project_path_ = path, app.save_project(path); break;
    case FileKind::ExportGlb: glb_path_ = path, app.export_glb(path); break;
    case FileKind::ExportObjFolder: export_dir_ = path, app.export_obj(path); break;
    case FileKind::LoadImage: decal_path_ = path, app.load_decal(path); break;
    case FileKind::Screenshot: screenshot_path_ = path, app.screenshot(path); break;
    case FileKind::LoadBrushPreset: preset_path_ = path, app.load_brush_preset(path); break;
    case FileKind::SaveBrushPreset: preset_path_ = path, app.save_brush_preset(path); break;
  }
}

void StudioUi::browser_window(App& app) {
  if (!browser_) return;
  const char* id = "Choose a file";
  if (!ImGui::IsPopupOpen(id)) ImGui::OpenPopup(id);
  ImGui::SetNextWindowSize(ImVec2(560, 420), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(id, nullptr)) return;
  open_modal_ = id;
  if (ImGui::IsWindowAppearing()) std::cout << "adaptex-studio: dialog: " << id << std::endl;
  ImGui::TextUnformatted(browser_->title);
  ImGui::InputText("Folder", &browser_dir_);
  const std::filesystem::path dir(browser_dir_);
  std::optional<std::string> chosen;
  ImGui::BeginChild("entries", ImVec2(0, -2.5f * ImGui::GetFrameHeightWithSpacing()), true);
  if (ImGui::Selectable("[..]", false, ImGuiSelectableFlags_AllowDoubleClick) && ImGui::IsMouseDoubleClicked(0))
    browser_dir_ = dir.parent_path().string();
  for (const BrowserEntry& e : list_folder(dir, browser_->folder ? std::vector<std::string>{} : browser_->extensions)) {
    if (browser_->folder && !e.folder) continue;
    const std::string label = e.folder ? "[" + e.name + "]" : e.name;
    if (!ImGui::Selectable(label.c_str(), browser_name_ == e.name, ImGuiSelectableFlags_AllowDoubleClick)) continue;
    browser_name_ = e.name;
    if (!ImGui::IsMouseDoubleClicked(0)) continue;
    if (e.folder && !browser_->folder) browser_dir_ = (dir / e.name).string(), browser_name_.clear();
    else chosen = (dir / e.name).string();
  }
  ImGui::EndChild();
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();  // type a name (or a whole path) at once
  const bool enter = ImGui::InputText("Name", &browser_name_, ImGuiInputTextFlags_EnterReturnsTrue);
  if (ImGui::IsItemActive() && !browser_ready_) {  // scripted tests type once this is printed
    std::cout << "adaptex-studio: file browser: " << browser_->title << std::endl;
    browser_ready_ = true;
  }
  if ((ImGui::Button(browser_->save ? "Save" : "Open") || enter)) {
    chosen = browser_name_.empty() ? (browser_->folder ? browser_dir_ : std::string()) : (dir / browser_name_).string();
    if (chosen->empty()) chosen.reset();
  }
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel (Esc)") || escape_pressed();
  if (chosen || cancel) {
    const FileKind kind = browser_->kind;
    browser_.reset();
    ImGui::CloseCurrentPopup();
    if (chosen) act(app, kind, *chosen);
  }
  ImGui::EndPopup();
}

void StudioUi::help_window(App& app) {
  ImGui::SetNextWindowPos(ImVec2(app.camera().width * 0.5f, app.camera().height * 0.5f), ImGuiCond_Appearing,
                          ImVec2(0.5f, 0.5f));
  if (!ImGui::Begin("Shortcuts (F1)", &app.view().show_help, ImGuiWindowFlags_AlwaysAutoResize)) return ImGui::End();
  if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg)) {
    for (const Shortcut& k : shortcuts()) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(k.keys);
      ImGui::TableSetColumnIndex(1);
      ImGui::TextUnformatted(k.what);
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

bool StudioUi::path_row(const char* id, const char* hint, std::string& path, const char* button, Focus focus) {
  const ImGuiStyle& st = ImGui::GetStyle();
  const float bw = ImGui::CalcTextSize(button).x + 2 * st.FramePadding.x;
  ImGui::SetNextItemWidth(std::max(40.f, ImGui::GetContentRegionAvail().x - bw - st.ItemSpacing.x));
  if (focus_ == focus && focus != Focus::None) {
    ImGui::SetKeyboardFocusHere();
    focus_ = Focus::None;
  }
  const bool enter = ImGui::InputTextWithHint(id, hint, &path, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  return (ImGui::Button(button) || enter) && !path.empty();
}

void StudioUi::follow_suggestion(std::string& field, std::string& shown, const std::string& suggestion) {
  if (field != shown) return;  // edited by the user
  field = suggestion;
  shown = suggestion;
}

void StudioUi::save(App& app) {
  if (app.project_path().empty())
    app.save_project(project_path_);
  else
    app.save();
}

void StudioUi::file_panel(App& app) {
  if (path_row("##open", "mesh file or builtin:NAME", open_path_, "Open", Focus::OpenPath))
    app.request_open_mesh(open_path_);
  if (!app.recent_files().empty() && ImGui::BeginCombo("Recent", "recent files...")) {
    for (const auto& r : app.recent_files())
      if (ImGui::Selectable(r.c_str())) {
        open_path_ = r;
        app.request_open_mesh(r);
      }
    ImGui::EndCombo();
  }
  if (ImGui::Button("New")) app.request_new();
  ImGui::SameLine();
  ImGui::TextDisabled("%s", app.project_path().empty() ? "(no project file)" : app.project_path().c_str());
  // The proposed project and GLB files follow the model until the user edits them.
  follow_suggestion(project_path_, suggested_project_, app.suggested_path(FileKind::SaveProject).string());
  follow_suggestion(glb_path_, suggested_glb_, app.suggested_path(FileKind::ExportGlb).string());
  if (path_row("##project", "project file (.adaptex)", project_path_, "Save As", Focus::ProjectPath))
    app.save_project(project_path_);
  trace("Save As");
  if (ImGui::Button("Save (Ctrl+S)")) save(app);
  ImGui::SameLine();
  if (ImGui::Button("Open project")) app.request_open_project(project_path_);
  if (path_row("##obj", "export folder", export_dir_, "Export OBJ")) app.export_obj(export_dir_);
  if (path_row("##glb", "GLB file", glb_path_, "Export GLB")) app.export_glb(glb_path_);
  trace("Export GLB");
  if (path_row("##png", "screenshot PNG", screenshot_path_, "Screenshot")) app.screenshot(screenshot_path_);
  if (path_row("##decal", "decal image (PNG)", decal_path_, "Load decal", Focus::DecalPath)) app.load_decal(decal_path_);
  if (app.decal_image()) stencil_controls(app);
  ImGui::BeginDisabled(!app.can_undo());
  if (ImGui::Button("Undo")) app.undo();
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!app.can_redo());
  if (ImGui::Button("Redo")) app.redo();
  ImGui::EndDisabled();
}

void StudioUi::stencil_controls(App& app) {
  float op = float(app.decal_opacity());
  if (ImGui::SliderFloat("Decal opacity", &op, 0.f, 1.f)) app.decal_opacity() = op;
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("Stencil: right drag moves, Shift scales, Ctrl rotates");
  ImGui::PopStyleColor();
  if (ImGui::Button("Project stencil (P)")) app.project_decal(app.decal_opacity());
  ImGui::SameLine();
  if (ImGui::Button("Fit")) app.stencil() = fit_stencil(app.camera(), app.stencil() ? app.stencil()->aspect : 1.0);
  ImGui::SameLine();
  if (ImGui::Button("Remove")) app.clear_decal();
}

void StudioUi::brush_panel(App& app) {
  BrushSettings& b = app.brush();
  int tool = int(b.tool);
  ImGui::RadioButton("Brush (B)", &tool, 0);
  ImGui::SameLine();
  ImGui::RadioButton("Eraser (E)", &tool, 1);
  ImGui::SameLine();
  ImGui::RadioButton("Pick (I)", &tool, 2);
  b.tool = Tool(tool);
  stamp_option(app, [this](const char* id) { trace(id); });
  ImGui::Checkbox("Layers and channels", &show_material_);
  tooltip("The Material window: the layers (add, delete, reorder, hide, opacity, blend mode) and the "
          "channels the brush paints (base colour, roughness, metallic, height)");
  trace("Layers and channels");
  float c[3] = {float(b.color.x()), float(b.color.y()), float(b.color.z())};
  if (ImGui::ColorEdit3("Colour", c)) b.color = Vec3(c[0], c[1], c[2]);
  float h = float(b.hardness), o = float(b.opacity), s = float(b.spacing);
  ImGui::Checkbox("Screen-space radius", &b.screen_space);
  tooltip("On: the brush keeps its size on the screen while you zoom (a stroke takes its size in the model "
          "where it starts). Off: the size is fixed on the model.");
  if (b.screen_space) {
    float px = float(b.pixel_radius);
    if (ImGui::SliderFloat("Radius px", &px, float(kMinPixelRadius), 300.f, "%.0f", ImGuiSliderFlags_Logarithmic))
      b.pixel_radius = px;
  } else {
    float r = float(b.radius);
    if (ImGui::SliderFloat("Radius", &r, 0.001f, 0.25f, "%.4f", ImGuiSliderFlags_Logarithmic)) b.radius = r;
  }
  tooltip("[ and ] change it; F then move the mouse resizes it on the model (click to keep, Esc to cancel).");
  ImGui::TextDisabled("  = %.4g model units here", app.world_radius());
  if (ImGui::SliderFloat("Hardness", &h, 0.f, 1.f)) b.hardness = h;
  if (ImGui::SliderFloat("Opacity", &o, 0.f, 1.f)) b.opacity = o;
  if (ImGui::SliderFloat("Spacing", &s, 0.02f, 2.f, "%.2f")) b.spacing = s;
  const char* axes[] = {"off", "X", "Y", "Z"};
  int ax = b.symmetry_axis + 1;
  if (ImGui::Combo("Symmetry", &ax, axes, 4)) b.symmetry_axis = ax - 1;
  Vec3 bg = app.history().background();
  float pb[3] = {float(bg.x()), float(bg.y()), float(bg.z())};
  if (ImGui::ColorEdit3("Paper", pb, ImGuiColorEditFlags_NoInputs)) app.set_background_colour(Vec3(pb[0], pb[1], pb[2]));
  // A section opened at the panel's bottom scrolls into view.
  const bool pressure = ImGui::TreeNode("Pen pressure");
  const bool pressure_opened = ImGui::IsItemToggledOpen();
  tooltip("How a tablet pen's pressure scales the radius and the opacity of each dab (a mouse: pressure 1).");
  trace("Pen pressure");
  if (pressure) {
    pressure_panel(b, [this](const char* id) { trace(id); });
    if (pressure_opened) ImGui::SetScrollHereY(1.0f);
    ImGui::TreePop();
  }
  const bool presets = ImGui::TreeNode("Presets");
  const bool presets_opened = ImGui::IsItemToggledOpen();
  trace("Presets");
  if (presets) {
    preset_panel(app, preset_path_, [this](const char* id) { trace(id); }, [&](FileKind k) { choose(app, k); });
    if (presets_opened) ImGui::SetScrollHereY(1.0f);
    ImGui::TreePop();
  }
}

void StudioUi::trace(const char* id) {
  if (!trace_) return;
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  const std::pair<int, int> at{int(0.5f * (a.x + b.x)), int(0.5f * (a.y + b.y))};
  auto [it, added] = traced_.emplace(id, at);
  if (!added && it->second == at) return;
  it->second = at;
  std::cout << "adaptex-studio: ui " << id << " at " << at.first << " " << at.second << std::endl;
}

void StudioUi::material_window(App& app, float top) {
  if (app.layered() && !shown_layered_) show_material_ = true;  // opens when the document becomes layered
  shown_layered_ = app.layered();
  if (!app.has_model() || !show_material_) return;
  const float w = kMaterialWidth;
  ImGui::SetNextWindowPos(ImVec2(float(app.camera().width) - w, top), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(w, 0), ImGuiCond_Always);
  // Many layers scroll inside the window instead of running off the screen.
  const float bottom = ImGui::GetFrameHeight() + 8;  // above the status line, as the side panel
  ImGui::SetNextWindowSizeConstraints(ImVec2(w, 0), ImVec2(w, std::max(120.f, float(app.camera().height) - top - bottom)));
  ImGui::Begin("Material", &show_material_,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  pbr_checkbox(app.view());
  ImGui::PushItemWidth(-ImGui::CalcTextSize("Roughness ").x);
  if (ImGui::CollapsingHeader("Layers", ImGuiTreeNodeFlags_DefaultOpen)) layers_panel(app);
  if (ImGui::CollapsingHeader("Brush channels", ImGuiTreeNodeFlags_DefaultOpen)) channels_panel(app);
  if (ImGui::CollapsingHeader("Mask and fill", ImGuiTreeNodeFlags_DefaultOpen))
    mask_panel(app, [this](const char* id) { trace(id); });
  ImGui::PopItemWidth();
  ImGui::End();
}

void StudioUi::layers_panel(App& app) {
  // Until layered: the history is one base-colour layer (named as material_from_v1 names it).
  MaterialStrokeFile single;
  if (!app.material()) single.layers.push_back(MaterialLayer{"Layer 1", true, 1, BlendMode::Normal, {}, {}});
  const MaterialStrokeFile& file = app.material() ? app.material()->file() : single;
  const int n = int(file.layers.size()), active = app.material() ? app.material()->active() : n - 1;
  // The edit waits until the panel is drawn: it replaces the document that `file` refers to.
  std::function<void(MaterialDocument&)> edit;
  for (int i = n - 1; i >= 0; --i) {  // the top layer first, as painting programs list them
    const MaterialLayer& l = file.layers[size_t(i)];
    ImGui::PushID(i);
    bool visible = l.visible;
    if (ImGui::Checkbox("##visible", &visible))
      edit = [i, visible](MaterialDocument& d) { d.set_visible(i, visible); };
    tooltip("Show or hide the layer");
    trace(("layer " + std::to_string(i + 1) + " visible").c_str());
    ImGui::SameLine();
    // Two lines that fit the window's width: the name (shortened with "..."), then its settings.
    char details[96];
    std::snprintf(details, sizeof details, "%s, %.0f %%, %zu strokes", blend_mode_name(l.blend), 100 * l.opacity,
                  app.material() ? l.strokes.size() : app.history().strokes().size());
    const std::string label = fit_text(l.name, ImGui::GetContentRegionAvail().x) + "\n" + details;
    if (ImGui::Selectable(label.c_str(), i == active) && i != active)
      edit = [i](MaterialDocument& d) { d.set_active(i); };
    trace(("layer " + std::to_string(i + 1)).c_str());
    ImGui::PopID();
  }
  if (ImGui::Button("Add layer")) edit = [](MaterialDocument& d) { d.add_layer(""); };
  trace("Add layer");
  ImGui::SameLine();
  ImGui::BeginDisabled(n < 2);
  if (ImGui::Button("Delete")) edit = [active](MaterialDocument& d) { d.delete_layer(active); };
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(active >= n - 1);
  if (ImGui::ArrowButton("##up", ImGuiDir_Up)) edit = [active](MaterialDocument& d) { d.move_layer(active, active + 1); };
  ImGui::EndDisabled();
  tooltip("Move the layer up");
  ImGui::SameLine();
  ImGui::BeginDisabled(active <= 0);
  if (ImGui::ArrowButton("##down", ImGuiDir_Down))
    edit = [active](MaterialDocument& d) { d.move_layer(active, active - 1); };
  ImGui::EndDisabled();
  tooltip("Move the layer down");
  const MaterialLayer& l = file.layers[size_t(active)];
  float opacity = float(l.opacity);
  // A drag is one undo step: every frame after the first continues it.
  if (ImGui::SliderFloat("Opacity##layer", &opacity, 0.f, 1.f, "%.2f"))
    edit = [active, opacity, merge = !ImGui::IsItemActivated()](MaterialDocument& d) {
      d.set_opacity(active, double(opacity), merge);
    };
  int blend = int(l.blend);
  const char* modes[] = {"normal", "multiply", "screen", "overlay", "add", "subtract"};
  static_assert(int(BlendMode::Subtract) == 5, "one name per blend mode");
  if (ImGui::Combo("Blend", &blend, modes, 6))
    edit = [active, blend](MaterialDocument& d) { d.set_blend(active, BlendMode(blend)); };
  if (!app.layered())
    ImGui::TextDisabled("One base-colour layer: Add layer or another\nchannel makes it a layered material.");
  if (edit) app.edit_material(edit);
}

void StudioUi::channels_panel(App& app) {
  BrushSettings& b = app.brush();
  auto channel = [&](const char* label, Channel c) {
    bool on = (b.channels & channel_bit(c)) != 0;
    if (ImGui::Checkbox(label, &on)) b.channels = on ? b.channels | channel_bit(c) : b.channels & ~channel_bit(c);
    trace(label);
    ImGui::SameLine(ImGui::CalcTextSize("Base colour ").x + 40);
  };
  channel("Base colour", Channel::BaseColor);
  float c[3] = {float(b.color.x()), float(b.color.y()), float(b.color.z())};
  if (ImGui::ColorEdit3("##colour", c, ImGuiColorEditFlags_NoInputs)) b.color = Vec3(c[0], c[1], c[2]);
  const std::pair<const char*, Channel> scalars[] = {
      {"Roughness", Channel::Roughness}, {"Metallic", Channel::Metallic}, {"Height", Channel::Height}};
  for (const auto& [label, ch] : scalars) {
    channel(label, ch);
    double& v = ch == Channel::Roughness ? b.roughness : ch == Channel::Metallic ? b.metallic : b.height;
    float f = float(v);
    ImGui::PushID(label);
    if (ImGui::SliderFloat("##value", &f, 0.f, 1.f, "%.2f")) v = f;
    ImGui::PopID();
  }
  if (b.channels == 0) ImGui::TextColored(ImVec4(1, 0.5f, 0.3f, 1), "The brush paints no channel");
}

void StudioUi::pbr_checkbox(ViewSettings& v) {
  ImGui::Checkbox("Lit material preview (V)", &v.pbr);
  tooltip("Shades the base colour with the roughness, metallic and the normal derived from the height, "
          "under a sky and ground and one key light; off: the base colour alone.");
  trace("Lit material preview");
}

void StudioUi::view_panel(App& app) {
  ViewSettings& v = app.view();
  ImGui::Checkbox("Wireframe (W)", &v.wireframe);
  pbr_checkbox(v);
  float c[3] = {float(v.background.x()), float(v.background.y()), float(v.background.z())};
  if (ImGui::ColorEdit3("Background", c)) v.background = Vec3(c[0], c[1], c[2]);
  if (ImGui::Button("Frame (F)")) app.frame_model();
  ImGui::TextWrapped("Left drag paints. Right/middle drag or Alt+left orbits, Shift+middle pans, wheel zooms.");
}

void StudioUi::adapt_panel(App& app) {
  PaintSessionOptions& o = app.session_options();
  AdaptOptions& a = o.adapt;
  bool changed = false;
  if (const std::string note = app.atlas_adaptation(); !note.empty()) ImGui::TextWrapped("%s.", note.c_str());
  std::vector<const char*> names;
  const auto& modes = adaptex::adapt_modes();
  int m = 0;
  for (size_t k = 0; k < modes.size(); ++k) {
    names.push_back(adaptex::to_string(modes[k]));
    if (modes[k] == a.mode) m = int(k);
  }
  if (ImGui::Combo("Mode", &m, names.data(), static_cast<int>(names.size()))) {
    a.mode = modes[size_t(m)];
    changed = true;
  }
  std::string methods = "How the texture layout follows your paint (the registered methods):";
  for (const AdaptMethodInfo* info : adapt_methods()) methods += "\n" + info->name + ": " + info->description;
  tooltip(methods.c_str());
  bool each = o.schedule == ReparamSchedule::EachStroke;
  if (ImGui::Checkbox("After every stroke", &each)) {
    o.schedule = each ? ReparamSchedule::EachStroke : ReparamSchedule::End;
    changed = true;
  }
  tooltip("Re-fit the layout in the background after every stroke, at a cost that does not grow with "
          "the number of strokes; after a 2 s pause it settles on the layout the whole history gives. "
          "Off: only when you press Re-parameterize now.");
  if (a.mode == AdaptMode::DensityFlow) {
    changed |= ImGui::Checkbox("Refine the mesh", &a.refine.enabled);
    tooltip("Split triangles that are too large to follow the layout's change inside painted areas. The "
            "surface keeps its shape; exports carry the extra triangles. Off keeps your vertices.");
  } else if (a.mode != AdaptMode::None) {
    float al = float(a.thesis.alpha), be = float(a.thesis.beta);
    if (ImGui::SliderFloat("alpha", &al, 0.f, 2.f)) a.thesis.alpha = al, changed = true;
    tooltip("How much the surface's own stretch counts where there is paint (thesis alpha).");
    if (ImGui::SliderFloat("beta", &be, 0.f, 2.f)) a.thesis.beta = be, changed = true;
    tooltip("How much the painted detail counts (thesis beta): higher gathers more texels on detail.");
    if (a.mode == AdaptMode::TwoStage) {
      changed |= ImGui::InputInt("Coarse grid", &a.thesis.coarse_grid);
      tooltip("Cells per side of the first, coarse grid: moves texels between large regions.");
    }
    changed |= ImGui::InputInt("Fine grid", &a.thesis.fine_grid);
    tooltip("Cells per side of the fine grid: spreads texels around small detail.");
    a.thesis.coarse_grid = std::clamp(a.thesis.coarse_grid, 2, kMaxGridCells);
    a.thesis.fine_grid = std::clamp(a.thesis.fine_grid, 2, kMaxGridCells);
  }
  const char* sizes[] = {"256", "512", "1024", "2048", "4096"};
  int si = std::clamp(int(std::lround(std::log2(o.texture_size))) - 8, 0, 4);
  if (ImGui::Combo("Texture size", &si, sizes, 5)) o.texture_size = 256 << si, changed = true;
  tooltip("Width and height of the texture in texels.");
  if (changed) app.session_options_changed();
  if (ImGui::Button("Re-parameterize now")) app.request_adapt();
  tooltip("Fit the layout to everything painted so far, now (also when After every stroke is off).");
  ImGui::Checkbox("Checker on the model (C)", &app.view().checker);
  tooltip("A checker of equal texel blocks on the model: small squares = many texels there. Painted areas "
          "get smaller squares when the layout adapts.");
  bool fixed = app.view().fixed_layout;
  if (ImGui::Checkbox("Show the fixed layout (L)", &fixed)) app.toggle_fixed_layout();
  tooltip("Shows the same strokes painted on the layout that does not adapt, at the same texture size: "
          "compare the sharpness (and the checker) with the adaptive one.");
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("Every re-parameterization starts from the initial layout, with the whole history.");
  ImGui::PopStyleColor();
}

void StudioUi::inspect_window(App& app, float top) {
  ImGui::SetNextWindowSize(ImVec2(340, std::min(560.f, float(app.camera().height) - top - 48)), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowPos(ImVec2(float(app.camera().width) - 348, top + 8), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Inspect", &show_inspect_)) return ImGui::End();
  const char* modes[] = {"texture", "texture + UV", "importance", "stretch", "L_s^2", "fixed vs adaptive",
                         "density"};
  ImGui::Combo("Show", &inspect_mode_, modes, 7);
  ImGui::Checkbox("optimized grid", &inspect_grid_);
  const ImageRGBA8* tex = app.texture();
  const Parameterization* p = app.param();
  const AdaptMaps* maps = app.adapt_maps();
  if (!tex || !p) {
    ImGui::TextDisabled("no texture yet");
    return ImGui::End();
  }
  if (maps)
    ImGui::Text("last re-parameterization: %s, damping %.2f", maps->accepted ? "accepted" : "kept previous (safeguard)",
                maps->damping);
  const float w = std::max(64.f, ImGui::GetContentRegionAvail().x);
  if (inspect_mode_ == 5) {
    const Comparison* c = app.comparison();
    if (ImGui::Button(app.compare_running() ? "comparing..." : "Compare now") && !app.compare_running())
      app.request_compare();
    if (!c) {
      ImGui::TextWrapped("Paints the same strokes on the fixed (unwrap) parameterization at the same texture size "
                         "and measures both against the exact stroke signal.");
      return ImGui::End();
    }
    const std::uint64_t key = reinterpret_cast<std::uintptr_t>(c) * 31 + 5;
    if (key != inspect_key_) {
      inspect_key_ = key;
      ImageRGBA8 a = draw_uv_layout(*c->fixed_param, &c->fixed_texture, 512);
      ImageRGBA8 b = draw_uv_layout(*c->adaptive_param, &c->adaptive_texture, 512);
      compare_tex_[0] = app.renderer().ui_image(1, a);
      compare_tex_[1] = app.renderer().ui_image(2, b);
    }
    const float half = w * 0.5f - 4;
    ImGui::Text("fixed: %.2f dB", c->psnr_fixed);
    ImGui::SameLine(half + 8);
    ImGui::Text("adaptive: %.2f dB", c->psnr_adaptive);
    ImGui::Image(compare_tex_[0], ImVec2(half, half), ImVec2(0, 1), ImVec2(1, 0));
    ImGui::SameLine();
    ImGui::Image(compare_tex_[1], ImVec2(half, half), ImVec2(0, 1), ImVec2(1, 0));
    ImGui::TextWrapped("%zu strokes, same texture size; PSNR over 200k surface samples", c->strokes);
    return ImGui::End();
  }
  const std::uint64_t key = (app.surface_serial() << 24) ^ (app.history().version() << 8) ^
                            (std::uint64_t(inspect_mode_) << 1) ^ std::uint64_t(inspect_grid_);
  if (key != inspect_key_ && (++inspect_frames_ % 10 == 1 || app.idle())) {
    inspect_key_ = key;
    const ImageF* map = !maps                ? nullptr
                        : inspect_mode_ == 2 ? &maps->importance
                        : inspect_mode_ == 3 ? &maps->stretch
                        : inspect_mode_ == 4 ? &maps->ls2
                        : inspect_mode_ == 6 ? &maps->density
                                             : nullptr;
    if (inspect_mode_ >= 2 && map && map->width > 0) {
      inspect_img_ = heat_image(inspect_mode_ == 6 ? scaled_to_max(*map) : *map);
    } else if (inspect_mode_ == 1) {
      inspect_img_ = draw_uv_layout(*p, tex, std::min(1024, tex->width));
    } else {
      inspect_img_ = *tex;
    }
    if (inspect_grid_ && maps) {
      for (const GridWarp* g : {&maps->coarse, &maps->fine}) {
        if (g->n <= 0) continue;
        const double W = inspect_img_.width, H = inspect_img_.height;
        const int step = std::max(1, g->n / 32);  // at most ~32 lines per direction
        const std::array<uint8_t, 3> col = g == &maps->coarse ? std::array<uint8_t, 3>{255, 200, 0}
                                                              : std::array<uint8_t, 3>{0, 160, 255};
        for (int j = 0; j <= g->n; j += (g == &maps->coarse ? 1 : step))
          for (int i = 0; i < g->n; ++i)
            draw_line(inspect_img_, g->at(i, j).x() * W, g->at(i, j).y() * H, g->at(i + 1, j).x() * W,
                      g->at(i + 1, j).y() * H, col);
        for (int i = 0; i <= g->n; i += (g == &maps->coarse ? 1 : step))
          for (int j = 0; j < g->n; ++j)
            draw_line(inspect_img_, g->at(i, j).x() * W, g->at(i, j).y() * H, g->at(i, j + 1).x() * W,
                      g->at(i, j + 1).y() * H, col);
      }
    }
    inspect_tex_ = app.renderer().ui_image(0, inspect_img_);
  }
  if (inspect_mode_ >= 2 && !maps) ImGui::TextDisabled("maps appear after the first re-parameterization (Adapt)");
  if (maps && inspect_mode_ >= 2 && inspect_mode_ != 5) {
    const ImageF* shown = inspect_mode_ == 2 ? &maps->importance : inspect_mode_ == 3 ? &maps->stretch
                        : inspect_mode_ == 4 ? &maps->ls2 : &maps->density;
    if (shown->width == 0) ImGui::TextDisabled("this map is not used by the %s method", to_string(app.session_options().adapt.mode));
  }
  // ImageRGBA8 rows start at v = 0 (bottom): flip vertically for display.
  if (inspect_tex_) ImGui::Image(inspect_tex_, ImVec2(w, w), ImVec2(0, 1), ImVec2(1, 0));
  inspect_legend(maps);
  ImGui::End();
}

void StudioUi::inspect_legend(const AdaptMaps* maps) const {
  ImGui::PushTextWrapPos(0);
  switch (inspect_mode_) {
    case 0: ImGui::TextUnformatted("The texture as stored: every island is a piece of the surface (a chart)."); break;
    case 1:
      ImGui::TextUnformatted("The texture with the layout's triangles: a triangle that is large here gets many "
                             "texels on the model.");
      break;
    case 2:
      heat_bar("no painted detail", "most detail");
      ImGui::TextUnformatted("Importance: how much painted detail each part of the layout holds.");
      break;
    case 3:
      heat_bar("even", "most stretched");
      ImGui::TextUnformatted("Stretch: where the layout spreads texels thinly over the surface.");
      break;
    case 4:
      heat_bar("low", "high");
      ImGui::TextUnformatted("L_s^2: the texture-stretch error of the painted signal, where detail is lost.");
      break;
    case 6: {
      char hi[48];
      std::snprintf(hi, sizeof hi, "%.1fx the mean", maps ? max_value(maps->density) : 0.f);
      heat_bar("few texels", hi);
      ImGui::TextUnformatted("Density: the texels per area the layout aims at; red gets the most.");
      break;
    }
    default: break;
  }
  if (inspect_grid_ && maps && inspect_mode_ != 5 && (maps->coarse.n > 0 || maps->fine.n > 0))
    ImGui::TextUnformatted("Grid lines: orange = coarse grid, blue = fine grid, as optimized (uniform = no change).");
  ImGui::PopTextWrapPos();
}

void StudioUi::collect_messages(App& app) {
  const auto& msgs = app.messages();
  if (msgs.size() < shown_messages_) shown_messages_ = 0;
  for (; shown_messages_ < msgs.size(); ++shown_messages_) {
    if (msgs[shown_messages_].error) {
      error_text_ = msgs[shown_messages_].text;
    } else {  // saved, exported, loaded...: shown for a few seconds above the status line
      toast_text_ = msgs[shown_messages_].text;
      toast_until_ = ImGui::GetTime() + 4.0;
    }
  }
}

void StudioUi::working_window(App& app) {
  const auto pr = app.progress();
  if (!pr || !app.load_running()) return;
  ImGui::SetNextWindowPos(ImVec2(app.camera().width * 0.5f, app.camera().height * 0.5f), ImGuiCond_Always,
                          ImVec2(0.5f, 0.5f));
  ImGui::Begin("Working", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
  ImGui::TextUnformatted(pr->first.c_str());
  ImGui::ProgressBar(float(pr->second), ImVec2(360, 0));
  if (ImGui::Button("Cancel")) app.cancel_load();
  ImGui::End();
}

void StudioUi::error_prompt(App& app) {
  if (!begin_modal("Error", app)) return;
  open_modal_ = "Error";
  ImGui::PushTextWrapPos(520);
  ImGui::TextUnformatted(error_text_.c_str());
  ImGui::PopTextWrapPos();
  const bool key = escape_pressed() || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter), false);
  if (ImGui::Button("OK") || key) {
    error_text_.clear();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void StudioUi::recovery_prompt(App& app) {
  const RecoveryOffer* o = app.recovery_offer();
  const char* title = "Recover unsaved strokes?";
  if (!o || !begin_modal(title, app)) return;
  open_modal_ = title;
  const Project& p = o->project;
  const std::string owner = recovery_owner(p), current = app.current_file();
  ImGui::Text("adaptex-studio did not exit cleanly. %s, unsaved, on",
              strokes_text(p.strokes.strokes.size()).c_str());
  ImGui::Text("    %s", owner.c_str());
  if (!p.project_file.empty()) ImGui::Text("    (mesh %s)", p.mesh_path.c_str());
  ImGui::Text("were autosaved %s ago.", age_text(o->age_seconds).c_str());
  ImGui::Spacing();
  const bool theirs = !current.empty() && (current == owner || current == p.mesh_path || current == p.project_file);
  if (current.empty())
    ImGui::TextUnformatted("Recover opens it with them.");
  else if (theirs)
    ImGui::TextUnformatted("They belong to the file you opened. Recover restores them.");
  else
    ImGui::Text("They belong to that file, not to the one you opened (%s).\nRecover opens %s with them.",
                std::filesystem::path(current).filename().string().c_str(),
                std::filesystem::path(owner).filename().string().c_str());
  ImGui::TextDisabled("Recovery file: %s", o->file.string().c_str());
  ImGui::Spacing();
  // R, D and Esc are answered by App::on_key (keys pressed within one slow frame are not lost).
  if (ImGui::Button("Recover (R)")) app.accept_recovery();
  ImGui::SameLine();
  if (ImGui::Button("Discard (D)")) app.discard_recovery();
  ImGui::SameLine();
  if (ImGui::Button("Later (Esc)")) app.defer_recovery();
  ImGui::SameLine();
  ImGui::TextDisabled("Later keeps the file for the next start.");
  ImGui::EndPopup();
}

void StudioUi::native_wait(App& app) {
  const char* title = "File dialog";
  if (!begin_modal(title, app)) return;
  open_modal_ = title;
  ImGui::Text("%s: choose in the desktop's file dialog.", native_.request().title);
  if (ImGui::Button("Cancel (Esc)") || escape_pressed()) native_.cancel();
  ImGui::EndPopup();
}

void StudioUi::toast(App& app) {
  const float pad = ImGui::GetFrameHeight() + 16;
  ImGui::SetNextWindowPos(ImVec2(float(app.camera().width) - 12, float(app.camera().height) - pad), ImGuiCond_Always,
                          ImVec2(1, 1));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##toast", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40);
  ImGui::TextUnformatted(toast_text_.c_str());
  ImGui::PopTextWrapPos();
  ImGui::End();
}

void StudioUi::confirm_prompt(App& app) {
  const char* title = "Unsaved strokes";
  const auto& c = app.confirm();
  if (!c || !begin_modal(title, app)) return;
  open_modal_ = title;
  const char* what = c->action == Confirm::Action::Quit          ? "Quitting"
                     : c->action == Confirm::Action::OpenMesh    ? "Opening another mesh"
                     : c->action == Confirm::Action::OpenProject ? "Opening a project"
                     : c->action == Confirm::Action::Recover     ? "Recovering the autosaved strokes"
                                                                 : "Starting a new scene";
  ImGui::Text("%s loses the strokes painted since the last save.", what);
  ImGui::InputText("Save to", &app.confirm_save_path());
  // The S / D / Esc keys are answered by App::on_key.
  const bool save = ImGui::Button("Save (S)");
  ImGui::SameLine();
  const bool discard = ImGui::Button("Discard (D)");
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel (Esc)");
  if (save) {
    app.confirm_save(app.confirm_save_path());
  } else if (discard) {
    app.confirm_discard();
  } else if (cancel) {
    app.confirm_cancel();
  }
  ImGui::EndPopup();
}

void StudioUi::status_bar(App& app) {
  const float h = ImGui::GetFrameHeight() + 8;
  ImGui::SetNextWindowPos(ImVec2(0, float(app.camera().height) - h));
  ImGui::SetNextWindowSize(ImVec2(float(app.camera().width), h));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoBringToFrontOnFocus);
  std::string s = app.status_line();
  if (auto pr = app.progress(); pr && !app.load_running()) {
    char buf[32];
    std::snprintf(buf, sizeof buf, " (%.0f%%)", pr->second * 100);
    s += " | " + pr->first + buf;
  }
  ImGui::TextUnformatted(s.c_str());
  if (app.adapting()) {
    ImGui::SameLine();
    if (ImGui::SmallButton("Cancel")) app.cancel_adaptation();
  }
  ImGui::End();
}

}  // namespace adaptex::studio
