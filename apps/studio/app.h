#pragma once
/// \file app.h
/// The state and logic of adaptex-studio, independent of GLFW / OpenGL / ImGui. The App wires four
/// parts together and owns the settings:
///   - InputState (input.h): drags, UI capture, shortcuts;
///   - Painting (painting.h): model, surface, stroke history, the open stroke, picking, uploads;
///   - SurfaceJobs (surface_jobs.h): loading, canvas rebuilds, re-parameterization, comparison;
///   - ProjectStore (storage.h): project file, unsaved work, recovery file, recent files.
/// Adaptation: the studio paints with the library's PaintSessionOptions (settings.h; by default the
/// library's best method, density-flow). After every change of the history (schedule each-stroke) a
/// background job runs `adaptex paint --reparam end` on the whole history from the model's initial
/// layout (backend.h paint_history): warps never compose, and the layout is a function of the
/// history and the options, so undo, projects and recovery give back exactly the same layout.
/// The window layer forwards input events and calls the frame phases in a fixed order:
///   1. input events (on_* handlers: camera, dabs painted at once)   2. begin_frame(): finished
///   background jobs are swapped in, autosave   3. UI (ImGui, outside App)   4. render()
///   5. end_frame(): scripted screenshot, statistics.
#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/adapt/session.h"
#include "brush.h"
#include "camera.h"
#include "file_browser.h"
#include "input.h"
#include "material_doc.h"
#include "painting.h"
#include "renderer.h"
#include "settings.h"
#include "stencil.h"
#include "storage.h"
#include "surface_jobs.h"

namespace adaptex::studio {

/// What to do at start with recovery files left by sessions that did not end cleanly.
enum class RecoverMode {
  Ask,  ///< The UI asks Recover / Discard / Later (interactive starts).
  Yes,  ///< Recover the newest without asking.
  No,   ///< Leave them untouched, say so on stderr (scripted runs).
};

/// Options given on the command line.
struct AppOptions {
  std::filesystem::path config_dir;    ///< Recent files (empty: no config).
  std::filesystem::path recovery_dir;  ///< Recovery file folder (empty: no autosave).
  double autosave_delay = 2.0;         ///< Seconds after a change before the recovery file is written.
  RecoverMode recover = RecoverMode::Ask;  ///< Recovery files found at start (recover_at_start()).
};

/// A message for the status line / error popup.
struct Message {
  std::string text;
  bool error = false;
};

/// Timing statistics (frame time, dab-to-screen latency).
struct Stats {
  std::vector<double> frame_ms;       ///< CPU+GPU time of each frame (end_frame to end_frame).
  std::vector<double> dab_latency_ms; ///< First pending dab event -> end of the frame showing it.
  std::vector<int> dab_latency_frames;///< Frames between the dab and its display (1 = same frame).
  std::vector<double> dab_paint_ms;   ///< Time to paint one dab (incl. mirror) into the texture.
};

/// An action that would drop unsaved strokes, waiting for Save / Discard / Cancel.
struct Confirm {
  enum class Action { Quit, OpenMesh, OpenProject, New, Recover };
  Action action = Action::Quit;
  std::string path;       ///< File to open (OpenMesh, OpenProject) or recover (Recover).
  std::string save_path;  ///< Where Save writes (App::suggested_project_path(); the UI may edit it).
};

class App {
 public:
  using Clock = std::chrono::steady_clock;

  App(std::unique_ptr<Renderer> renderer, AppOptions options);
  /// Unsaved strokes are written to the recovery file; without any, it is removed.
  ~App();
  App(const App&) = delete;
  App& operator=(const App&) = delete;

  // ---- 1. input (window coordinates: origin top-left, y down) ----
  void on_resize(int width, int height);
  void on_mouse_button(MouseButton b, bool pressed, Mods mods);
  void on_cursor(double x, double y);
  void on_scroll(double steps);
  void on_key(int key, bool pressed, Mods mods);
  void on_drop(const std::vector<std::string>& paths);
  /// What the UI wants (ImGui io.WantCaptureMouse / WantCaptureKeyboard / WantTextInput of the last
  /// frame). While Save / Discard / Cancel is asked, S, D and Escape answer unless a text field has
  /// the keyboard (handled here, from the window's key events: a key pressed and released within one
  /// slow frame is never lost).
  void set_ui_capture(bool mouse, bool keyboard, bool text = false) { input_.set_ui_capture(mouse, keyboard, text); }

  // ---- 2, 4, 5. frame phases ----
  void begin_frame();
  void render();
  void end_frame();
  bool should_quit() const { return quit_; }

  // ---- unsaved work: these ask Save / Discard / Cancel (confirm()) when unsaved() ----
  /// Strokes that no project file holds (painted, replayed or recovered since the last save / open).
  bool unsaved() const;
  /// Quits (after Save / Discard / Cancel); a queued export is written first, and a second request
  /// quits without it.
  void request_quit();
  void request_open_mesh(const std::string& path);
  void request_open_project(const std::filesystem::path& path);
  void request_new();
  /// Opens \p path by what it is: a project (.adaptex, or a JSON project), a stroke file (replayed), an
  /// image (decal stencil), else a mesh (a drop on the window, the command line). Asks when unsaved.
  void request_open_file(const std::filesystem::path& path);
  /// The action waiting for an answer (the UI shows Save / Discard / Cancel).
  const std::optional<Confirm>& confirm() const { return confirm_; }
  /// Saves to \p path, then does the waiting action. \return false (nothing done) if saving failed
  bool confirm_save(const std::filesystem::path& path);
  /// Drops the unsaved strokes (and the recovery file), then does the waiting action.
  void confirm_discard();
  void confirm_cancel();
  /// The Save path of the waiting question. \pre confirm()
  std::string& confirm_save_path() { return confirm_->save_path; }
  /// Quits without asking (signals, scripted runs); unsaved strokes stay in the recovery file.
  void quit_now() { quit_ = true; }

  // ---- commands (UI, command line, tests); open_* and new_scene() do not ask ----
  /// Starts loading + unwrapping \p path in the background (replaces the current model when done).
  void open_mesh(const std::string& path);
  void cancel_load();
  void open_project(const std::filesystem::path& path);
  /// Closes the model (empty scene).
  void new_scene();
  /// Save As: writes the project to \p path, which becomes the project file. \return success
  bool save_project(const std::filesystem::path& path);
  /// Save: to the project file. \return false (with a message) when there is none yet
  bool save();
  /// The project file (empty: none yet).
  std::filesystem::path project_path() const { return store_.project_path(); }
  /// Where Save As proposes to write (suggested_path(FileKind::SaveProject)).
  std::string suggested_project_path() const { return suggested_path(FileKind::SaveProject).string(); }
  /// The folder file dialogs start in: the last one a file was opened, saved or exported in (kept in
  /// the config), else the mesh's folder, else the current folder.
  std::filesystem::path last_folder() const;
  /// What a dialog proposes: Save As the project file, else `<mesh stem>.adaptex`; Export GLB
  /// `<mesh stem>.glb`; Screenshot `<mesh stem>.png`; in last_folder(). Other kinds: last_folder().
  std::filesystem::path suggested_path(FileKind kind) const;
  /// Appends the strokes of a stroke file to the history (painted when the model is ready).
  void replay(const StrokeFile& file);
  /// Appends one finished stroke (brush or decal, the stroke-file contract) as if it had been painted:
  /// undoable, painted onto the canvas at the next frame and adapted to like a painted one (scripts,
  /// benchmarks). \throw InvalidInputError the stroke breaks the contract (the history is unchanged);
  /// Error no model, or a stroke is open
  void add_stroke(Stroke stroke);
  void undo();
  void redo();
  void frame_model();
  void set_background_colour(const Vec3& bg);  ///< Paint background (eraser colour); rebuilds.
  /// Exports OBJ+MTL+PNG / binary glTF. A layered material exports its settled result (what
  /// `adaptex paint` writes for the document): before the settle, the export waits for it without
  /// blocking (exporting()), the session settles at once, and the files are written when it arrives.
  void export_obj(const std::filesystem::path& dir);
  void export_glb(const std::filesystem::path& path);
  /// Exports waiting for the material session's settled result (written by a later begin_frame()).
  bool exporting() const { return !pending_exports_.empty(); }
  void save_history(const std::filesystem::path& path);
  void save_texture(const std::filesystem::path& path);
  /// Screenshot of the window (taken at the end of the current frame, UI included).
  void screenshot(const std::filesystem::path& path);
  /// Loads a decal image and shows it as a stencil over the view (fit_stencil), nothing projected yet.
  void load_decal(const std::filesystem::path& path);
  /// Projects the loaded decal image through its stencil (stencil.h) as a decal stroke, from the
  /// current view; the stencil stays for another projection.
  void project_decal(double opacity = 1.0);
  /// Removes the decal image and its stencil.
  void clear_decal();
  /// The stencil of the loaded decal image (nullopt without one); the UI and tests may edit it.
  std::optional<Stencil>& stencil() { return stencil_; }
  const std::optional<Stencil>& stencil() const { return stencil_; }
  /// Opacity the P key and the Project button project the stencil with.
  double& decal_opacity() { return decal_opacity_; }
  /// Opening a model that has its own UV atlas and base-colour texture: false (default) paints on
  /// them, true unwraps it afresh (`--unwrap`, *File → Fresh unwrap*). Changing it reopens the open
  /// model with the other layout, keeping the strokes.
  void set_unwrap(bool unwrap);
  bool unwrap() const { return has_model() ? painting_.model()->unwrap_asked : unwrap_; }
  /// A model opened on its own atlas gets its texture's size (default true; false after `--texture-size`).
  void set_texture_size_from_model(bool on) { size_from_texture_ = on; }
  /// The model is painted on its artist's atlas and texture (adaptation then keeps the atlas's
  /// charts and shared texels: atlas_adaptation()).
  bool on_artist_atlas() const { return has_model() && painting_.model()->base != nullptr; }
  /// How adaptation works on the artist's atlas, when it is on (empty: not on an atlas, or no method).
  std::string atlas_adaptation() const;
  /// Re-parameterizes now (with schedule each-stroke it also runs after every change).
  void request_adapt();
  /// A re-parameterization runs in the background (the status line's Cancel stops it).
  bool adapting() const { return jobs_.rebuild_adapting(); }
  /// Stops the running re-parameterization; the layout stays as it is until the next change of the
  /// history or options, or request_adapt().
  void cancel_adaptation();
  /// The UI changed session_options(): re-parameterize for them (schedule each-stroke).
  void session_options_changed();

  // ---- the layered material (material_doc.h, docs/studio.md "Layers and channels") ----
  /// The document is a layered material. Until the first layer edit (or a brush painting another
  /// channel than base colour) it is one base-colour layer: the stroke history (history()), painted
  /// dab by dab and adapted live. Layered, a background material session (live_material.h) composites
  /// and adapts each stroke incrementally, and after a pause settles on paint_material_history()
  /// (`adaptex paint` for the document as a version 2 file); other edits start a new session. The open
  /// stroke's base colour shows at once on the last composite.
  bool layered() const { return material_.has_value(); }
  /// The layered document (null: not layered).
  const MaterialDocument* material() const { return material_ ? &*material_ : nullptr; }
  /// The document as a stroke file of version 2 (a base-colour history: one layer, as version 1 reads).
  MaterialStrokeFile material_file() const;
  /// Makes the document layered (the history becomes "Layer 1") and applies \p edit to it; an edit
  /// that throws changes nothing and is reported as an error message. \return success
  bool edit_material(const std::function<void(MaterialDocument&)>& edit);
  /// Opens a version 2 stroke file as the document (replacing it; its undo history is dropped).
  void open_material(MaterialStrokeFile file);
  /// The strokes as a stroke file of version 2 (write_material_strokes), atomically.
  void save_material_strokes(const std::filesystem::path& path);
  /// Fills the active layer with the brush's channels and values (a fill stroke), or with \p mask its
  /// mask with the brush's mask value. \return false (with a message) if it cannot.
  bool fill_active(bool mask);
  /// The eyedropper on a layered material: the composited values of the brush's checked channels (all
  /// when none is checked) at \p h go into the brush (evaluated exactly, not read from the textures).
  void pick_channels(const Hit& h);
  /// Brush presets (brush_preset.h): save the brush's channels, values, radius, hardness, opacity,
  /// spacing, mask value and pressure curves; load them into the brush (a bad file: one error message,
  /// the brush unchanged). \return success
  bool save_brush_preset(const std::filesystem::path& path);
  bool load_brush_preset(const std::filesystem::path& path);
  /// Brush strokes go to the active layer's mask (BrushSettings::on_mask and the layer has one).
  bool painting_mask() const;
  /// The pen pressure of the next dabs, in [0,1] (tablet.h; 1 for a mouse).
  void set_pen_pressure(double p) { pen_pressure_ = std::clamp(p, 0.0, 1.0); }
  bool can_undo() const { return material_ ? material_->can_undo() : history().can_undo(); }
  bool can_redo() const { return material_ ? material_->can_redo() : history().can_redo(); }
  /// Version of the document: changes with every stroke, undo, redo and layer edit.
  std::uint64_t document_version() const;

  // ---- recovery files left by sessions that did not end cleanly (recovery.h) ----
  /// Applies AppOptions::recover once the command line's files are opened: Yes recovers the newest
  /// recovery file, No leaves every one untouched (one line each on stderr), Ask leaves them to the UI.
  void recover_at_start();
  /// The recovery file to ask about now (null: none). Asked with R (Recover), D (Discard) and Esc (Later).
  const RecoveryOffer* recovery_offer() const { return store_.recovery().next_offer(); }
  /// Recover: opens the offered file's mesh with its strokes, settings, view and project file (after
  /// Save / Discard / Cancel when this session has unsaved strokes). The strokes count as unsaved.
  void accept_recovery();
  /// Discard: deletes the offered recovery file.
  void discard_recovery();
  /// Later: keeps the offered file; asked again when its mesh or project is opened, and at the next start.
  void defer_recovery();
  /// The file this session works on, as the recovery question names it: the project file, else the
  /// mesh (also while it loads); empty: none.
  std::string current_file() const;

  // ---- queries ----
  bool has_model() const { return painting_.model() != nullptr; }
  /// True when no background job runs and the texture is up to date with the history and options.
  bool idle() const;
  /// Blocks until idle() (tests and scripted mode only). \return false on timeout
  bool wait_idle(double timeout_seconds);
  std::string mesh_path() const;
  /// The painted mesh: the model's, or its refinement after a density-flow re-parameterization.
  const TriMesh* mesh() const;
  const Parameterization* param() const;
  const ImageRGBA8* texture() const;
  const StrokeHistory& history() const { return painting_.history(); }
  Camera& camera() { return camera_; }
  BrushSettings& brush() { return brush_; }
  ViewSettings& view() { return view_; }
  /// Texture size and adaptation (the library's options; call session_options_changed() after edits).
  PaintSessionOptions& session_options() { return session_; }
  const PaintSessionOptions& session_options() const { return session_; }
  const BrushSettings& brush() const { return brush_; }
  const ViewSettings& view() const { return view_; }
  const std::vector<std::string>& recent_files() const { return store_.recent(); }
  /// Brush radius in world units at the surface under the cursor (else at the camera's target):
  /// what a stroke begun there records (brush.h).
  double world_radius() const;
  /// The brush circles to draw on the screen this frame (the cursor, its mirror with symmetry, the
  /// circle of an F resize): none while the mouse is over the UI or with the eyedropper.
  std::vector<ScreenCircle> brush_cursors() const;
  /// Ctrl+O was pressed since the last call: the UI shows the open-mesh dialog. \return whether it was
  bool take_open_dialog_request() { return std::exchange(open_dialog_requested_, false); }
  /// An F resize runs (the next click or F keeps it, Esc or a right click cancels it).
  bool resizing_brush() const { return resize_.has_value(); }
  /// The visible front-facing surface under window pixel (x, y).
  std::optional<Hit> pick(double x, double y) const;
  /// Painted colour at a hit (bilinear texture sample).
  Vec3 sample_colour(const Hit& h) const { return painting_.sample_colour(h); }
  bool painting() const { return painting_.stroke_open(); }
  const std::deque<Message>& messages() const { return messages_; }
  void clear_messages() { messages_.clear(); }
  std::string status_line() const;
  /// Background work in progress: (label, fraction) or nullopt.
  std::optional<std::pair<std::string, double>> progress() const;
  bool load_running() const { return jobs_.loading(); }
  const Stats& stats() const { return stats_; }
  void reset_stats() { stats_ = Stats(); }
  Renderer& renderer() { return *renderer_; }
  const std::optional<ImageRGBA8>& decal_image() const { return decal_image_; }
  /// Phase times of the last re-parameterization (name, ms).
  const std::vector<std::pair<std::string, double>>& last_cycle() const { return last_cycle_; }
  /// Starts the fixed-vs-adaptive comparison in the background.
  void request_compare();
  /// The L key: shows the model with its fixed (initial) layout, the same strokes painted at the same
  /// texture size (the comparison's), instead of the adaptive one; again: back. Computed in the
  /// background when the comparison is missing or older than the history; painting returns to the
  /// adaptive layout.
  void toggle_fixed_layout();
  /// The 3-D view shows the fixed layout now (toggled on and its comparison is up to date).
  bool showing_fixed_layout() const { return shown_fixed_ != nullptr; }
  /// The last comparison (null before the first one).
  const Comparison* comparison() const { return comparison_.get(); }
  bool compare_running() const { return jobs_.comparing(); }
  /// Maps of the last re-parameterization (null before the first one).
  const AdaptMaps* adapt_maps() const { return maps_.get(); }
  /// The live session settles as soon as it has adapted the strokes so far, without waiting for a
  /// pause (scripts; wait_idle() does it too).
  void settle_adaptation_now() { jobs_.settle_live_now(); }
  /// The live each-stroke session adapting while painting (schedule each-stroke), or null.
  const LiveAdaptation* live_adaptation() const { return jobs_.live(); }
  /// The layered material's session (null: none), and how many were started (a stroke is fed to the
  /// running one; a layer edit, undo or redo starts another).
  const LiveMaterial* live_material() const { return jobs_.live_material(); }
  int material_sessions_started() const { return jobs_.material_starts(); }
  /// The surface shown (null: no model).
  const Surface* surface() const { return painting_.surface(); }
  /// Canvas (texture) generation counter: changes whenever a new texture is swapped in.
  std::uint64_t surface_serial() const { return painting_.serial(); }
  std::filesystem::path recovery_path() const { return store_.recovery_path(); }

 private:
  /// Strokes and settings for the model being loaded.
  struct PendingLoad {
    std::vector<Stroke> strokes;
    std::optional<Vec3> background;
    bool from_project = false;       ///< The strokes are what project_path holds (nothing unsaved).
    std::filesystem::path project_path;
    bool reload = false;  ///< The same model unwrapped again for another texture size (history kept).
    std::optional<Camera> camera;  ///< The project's view (else the model is framed).
    bool recovered = false;        ///< Strokes from a recovery file: unsaved, even when none.
    bool relayout = false;         ///< A reload for another layout (set_unwrap()), not a texture size.
    std::optional<bool> unwrap;    ///< The project's layout (else App::unwrap_).
    std::optional<size_t> adapted_strokes;  ///< Project::adapted_strokes.
    std::optional<MaterialStrokeFile> material;  ///< Project::material.
    int active_layer = 0;                        ///< Project::active_layer.
  };

  void add_message(std::string text, bool error);
  void ask_or_do(Confirm c);
  void perform(const Confirm& c);
  Project snapshot() const;
  void apply_project(Project p, bool from_project, const std::filesystem::path& project_path);
  void history_changed();
  bool adapt_wanted() const;
  /// The adaptation method in effect (on an artist's atlas, any method but None adapts the atlas).
  AdaptMode adapt_mode() const;
  /// Adaptation runs in the live each-stroke session (schedule each-stroke, a method, strokes).
  bool adapts_live() const;
  void finish_live();
  /// After an export: says so if adaptation had not finished (what was shown was exported).
  void note_export_while_adapting();
  // painting
  Stroke brush_style() const;
  void begin_paint();
  void continue_paint(double x0, double y0, double x1, double y1);
  void paint_dab_at(const Hit& h, const Ray& ray);
  void end_paint();
  void eyedrop(double x, double y);
  /// A decal stroke of the loaded image through \p camera (project_decal, stamp_decal); on a layered
  /// material it paints \p channels (material_decal_stroke()).
  void record_decal(const DecalCamera& camera, double opacity, unsigned channels = channel_bit(Channel::BaseColor));
  /// BrushSettings::stamp: the loaded image stamped at the cursor. \pre a decal image is loaded
  void stamp_decal();
  void update_cursor();
  /// Model diagonal (1 without a model).
  double diagonal() const;
  /// The surface point the brush radius is measured at: under the cursor, else the camera's target.
  Vec3 brush_anchor() const;
  void start_resize();
  void end_resize(bool keep);
  void run_command(Command c);
  void answer_key(int key);
  void answer_recovery_key(int key);
  /// Takes the recovery file \p file and opens its session.
  void recover(const std::filesystem::path& file);
  /// Remembers the folder of a file opened, saved or exported (last_folder()).
  void note_folder(const std::filesystem::path& file);
  // jobs
  void poll_jobs();
  void finish_load(Job<LoadResult>& job);
  void finish_rebuild(Job<RebuildResult>& job);
  void maybe_start_rebuild();
  void maybe_unwrap_again();
  void start_rebuild(bool adapt);
  /// Uploads what the 3-D view shows: the painted surface, or the fixed layout (toggle_fixed_layout).
  void upload_view();

  // layered material (app_material.cpp)
  MaterialStroke material_brush_stroke(const Stroke& painted) const;
  /// The decal \p decal as a layer stroke painting \p channels: base colour from the image, roughness,
  /// metallic and height at the brush's values.
  MaterialStroke material_decal_stroke(Stroke decal, unsigned channels) const;
  /// Records a finished stroke: on the history, or on the active layer when layered.
  void record_stroke(Stroke s);
  /// Records \p m on the active layer (or its mask, for a brush stroke while painting the mask).
  /// \pre layered
  void record_material_stroke(MaterialStroke m);
  /// After an edit of the document other than record_stroke()'s: a new material session for it.
  void material_changed();
  /// Starts a material session when none serves the model, options and document. \return layered
  bool maybe_start_material();
  /// Shows the material session's newest surface.
  void finish_material();
  /// An export of the layered material: OBJ+MTL+PNG to a folder, or a GLB file.
  struct MaterialExport {
    bool glb = false;
    std::filesystem::path path;
    const Model* model = nullptr;  ///< The model it was asked for (another one drops it).
  };
  /// The surface shown is the settled result of the document, its model and options.
  bool material_settled() const;
  /// Writes \p e now when material_settled(), else queues it and asks the session to settle now.
  void export_material(MaterialExport e);
  /// Writes \p e from the settled surface shown. \pre material_settled()
  void write_material_export(const MaterialExport& e);
  /// Writes the queued exports once the settled result is shown (drops them for another model).
  void finish_exports();

  std::unique_ptr<Renderer> renderer_;
  AppOptions options_;
  std::deque<Message> messages_;  // before store_, which reports through add_message()
  Camera camera_;
  BrushSettings brush_;
  ViewSettings view_;
  PaintSessionOptions session_ = studio_session_options();

  InputState input_;
  Painting painting_;
  SurfaceJobs jobs_;
  ProjectStore store_;

  PendingLoad pending_;
  bool unwrap_ = false, size_from_texture_ = true;
  bool adapt_pending_ = false;  // the layout is not yet the one of the history and options
  std::optional<size_t> adapted_for_;   // strokes the adapted layout was made for (null: not adapted)
  std::optional<size_t> adapt_prefix_;  // the next adaptation is for the first so many strokes only
  std::vector<std::pair<std::string, double>> last_cycle_;
  std::shared_ptr<const AdaptMaps> maps_;
  std::string atlas_state_;  // what the last adaptation of the artist's atlas did (status line)
  std::shared_ptr<const Comparison> comparison_;
  std::uint64_t compare_version_ = ~0ull;  // history version the last comparison was started for
  std::shared_ptr<const Comparison> shown_fixed_;  // the comparison whose fixed layout the renderer holds
  std::optional<Confirm> confirm_;

  std::optional<Hit> cursor_hit_;
  std::optional<Clock::time_point> first_pending_dab_;
  int frames_since_dab_ = 0;
  std::optional<std::filesystem::path> pending_screenshot_;
  std::optional<ImageRGBA8> decal_image_;
  std::string decal_path_;
  std::optional<Stencil> stencil_;
  double decal_opacity_ = 1.0;
  std::optional<BrushResize> resize_;
  bool open_dialog_requested_ = false;
  Stats stats_;
  Clock::time_point last_frame_end_ = Clock::now();
  std::optional<MaterialDocument> material_;
  std::uint64_t material_generation_ = 0;  // changes with every change of the document (or a new one)
  std::vector<double> stroke_pressure_;  // the open stroke's pressure per dab
  std::vector<MaterialExport> pending_exports_;  // waiting for the settled result (export_material)
  double pen_pressure_ = 1;
  bool quit_ = false;
  bool quit_after_exports_ = false;  // a quit waits for the queued exports (finish_exports)
};

}  // namespace adaptex::studio
