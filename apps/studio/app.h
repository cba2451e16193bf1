#pragma once
/// \file app.h
/// The state and logic of adaptex-studio, independent of GLFW / OpenGL / ImGui: one App object owns
/// everything (model, parameterization, canvas, stroke history, camera, settings, background jobs).
/// The window layer forwards input events and calls the frame phases in a fixed order:
///   1. input events (on_* handlers: camera, dabs painted at once)   2. begin_frame(): finished
///   background jobs are swapped in, autosave   3. UI (ImGui, outside App)   4. render()
///   5. end_frame(): scripted screenshot / exit, statistics.
#include <chrono>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/strokes.h"
#include "backend.h"
#include "camera.h"
#include "history.h"
#include "jobs.h"
#include "ray_caster.h"
#include "renderer.h"
#include "settings.h"

namespace adaptex::studio {

/// Options given on the command line.
struct AppOptions {
  std::filesystem::path config_dir;    ///< Recent files (empty: no config).
  std::filesystem::path recovery_dir;  ///< Recovery file folder (empty: no autosave).
  double autosave_delay = 2.0;         ///< Seconds after a change before the recovery file is written.
  bool auto_recover = false;           ///< Accept a recovery file without asking.
};

/// A message for the status line / error popup.
struct Message {
  std::string text;
  bool error = false;
};

/// Maps of the last adaptive re-parameterization (Inspect panel).
struct AdaptMaps {
  ImageF importance, stretch, ls2;  ///< Over the previous parameterization's domain.
  GridWarp coarse, fine;            ///< Optimized grids (empty when not used).
  bool accepted = true;             ///< false: the safeguard kept the previous parameterization.
  double damping = 1;
};

/// Fixed vs adaptive parameterization on the same strokes at the same texture size (Inspect panel).
struct Comparison {
  std::shared_ptr<const Parameterization> fixed_param, adaptive_param;
  ImageRGBA8 fixed_texture, adaptive_texture;
  double psnr_fixed = 0, psnr_adaptive = 0;  ///< dB against the exact stroke signal (adaptex eval).
  size_t strokes = 0;
};

/// Timing statistics (frame time, dab-to-screen latency).
struct Stats {
  std::vector<double> frame_ms;       ///< CPU+GPU time of each frame (end_frame to end_frame).
  std::vector<double> dab_latency_ms; ///< First pending dab event -> end of the frame showing it.
  std::vector<int> dab_latency_frames;///< Frames between the dab and its display (1 = same frame).
  std::vector<double> dab_paint_ms;   ///< Time to paint one dab (incl. mirror) into the texture.
};

class App {
 public:
  using Clock = std::chrono::steady_clock;

  App(std::unique_ptr<Renderer> renderer, AppOptions options);
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
  /// What the UI wants (ImGui io.WantCaptureMouse / WantCaptureKeyboard of the last frame).
  void set_ui_capture(bool mouse, bool keyboard) {
    ui_mouse_ = mouse;
    ui_keyboard_ = keyboard;
  }

  // ---- 2, 4, 5. frame phases ----
  void begin_frame();
  void render();
  void end_frame();
  bool should_quit() const { return quit_; }
  void request_quit() { quit_ = true; }

  // ---- commands (UI, command line, tests) ----
  /// Starts loading + unwrapping \p path in the background (replaces the current model when done).
  void open_mesh(const std::string& path);
  void cancel_load();
  void open_project(const std::filesystem::path& path);
  void save_project(const std::filesystem::path& path);
  /// Appends the strokes of a stroke file to the history (painted when the model is ready).
  void replay(const StrokeFile& file);
  void undo();
  void redo();
  void frame_model();
  void set_background_colour(const Vec3& bg);  ///< Paint background (eraser colour); rebuilds.
  void export_obj(const std::filesystem::path& dir);
  void export_glb(const std::filesystem::path& path);
  void save_history(const std::filesystem::path& path);
  void save_texture(const std::filesystem::path& path);
  /// Screenshot of the window (taken at the end of the current frame, UI included).
  void screenshot(const std::filesystem::path& path);
  void load_decal(const std::filesystem::path& path);
  /// Projects the loaded decal image from the current view as a decal stroke.
  void project_decal(double opacity = 1.0);
  /// Re-runs the adaptive re-parameterization now (also runs after each stroke when enabled).
  void request_adapt();
  void accept_recovery();
  void discard_recovery();

  // ---- queries ----
  bool has_model() const { return model_ != nullptr; }
  /// True when no background job runs and the texture is up to date with the history.
  bool idle() const;
  /// Blocks until idle() (tests and scripted mode only). \return false on timeout
  bool wait_idle(double timeout_seconds);
  std::string mesh_path() const;
  const TriMesh* mesh() const;
  const Parameterization* param() const;
  const ImageRGBA8* texture() const;
  const StrokeHistory& history() const { return history_; }
  Camera& camera() { return camera_; }
  BrushSettings& brush() { return brush_; }
  ViewSettings& view() { return view_; }
  AdaptSettings& adapt() { return adapt_; }
  const AdaptSettings& adapt() const { return adapt_; }
  const BrushSettings& brush() const { return brush_; }
  const ViewSettings& view() const { return view_; }
  const std::vector<std::string>& recent_files() const { return recent_; }
  /// Brush radius in world units.
  double world_radius() const;
  /// The visible front-facing surface under window pixel (x, y).
  std::optional<Hit> pick(double x, double y) const;
  /// Painted colour at a hit (bilinear texture sample).
  Vec3 sample_colour(const Hit& h) const;
  bool painting() const { return stroke_open_; }
  const std::deque<Message>& messages() const { return messages_; }
  void clear_messages() { messages_.clear(); }
  std::string status_line() const;
  /// Background work in progress: (label, fraction) or nullopt.
  std::optional<std::pair<std::string, double>> progress() const;
  bool load_running() const;
  std::optional<std::filesystem::path> pending_recovery() const { return pending_recovery_; }
  const Stats& stats() const { return stats_; }
  void reset_stats() { stats_ = Stats(); }
  Renderer& renderer() { return *renderer_; }
  const std::optional<ImageRGBA8>& decal_image() const { return decal_image_; }
  /// Phase times of the last re-parameterization cycle (name, ms).
  const std::vector<std::pair<std::string, double>>& last_cycle() const { return last_cycle_; }
  /// Starts the fixed-vs-adaptive comparison in the background.
  void request_compare();
  /// The last comparison (null before the first one).
  const Comparison* comparison() const { return comparison_.get(); }
  bool compare_running() const;
  /// Maps of the last re-parameterization (null before the first one).
  const AdaptMaps* adapt_maps() const { return maps_.get(); }
  /// Canvas (texture) generation counter: changes whenever a new texture is swapped in.
  std::uint64_t surface_serial() const { return surface_serial_; }
  std::filesystem::path recovery_path() const;

 private:
  struct Model;
  struct Surface;
  struct LoadResult;
  struct RebuildResult;

  void add_message(std::string text, bool error);
  void begin_paint(double x, double y);
  void continue_paint(double x, double y);
  void end_paint();
  void paint_dab_at(const Hit& h, const Ray& ray);
  void eyedrop(double x, double y);
  void update_cursor(double x, double y);
  void poll_jobs();
  void maybe_start_rebuild();
  void start_rebuild(bool adapt);
  void swap_surface(std::unique_ptr<Surface> s);
  void autosave_tick();
  void add_recent(const std::string& path);
  void load_config();
  void save_config() const;
  Stroke brush_style() const;

  std::unique_ptr<Renderer> renderer_;
  AppOptions options_;
  Camera camera_;
  BrushSettings brush_;
  ViewSettings view_;
  AdaptSettings adapt_;
  StrokeHistory history_;

  std::shared_ptr<const Model> model_;
  std::unique_ptr<Surface> surface_;
  std::unique_ptr<Job<LoadResult>> load_job_;
  std::unique_ptr<Job<RebuildResult>> rebuild_job_;
  std::vector<std::unique_ptr<JobBase>> retired_jobs_;  // cancelled; destroyed (joined) once finished
  std::unique_ptr<Job<int>> autosave_job_;
  std::unique_ptr<Job<Comparison>> compare_job_;
  std::shared_ptr<const Comparison> comparison_;
  bool adapt_pending_ = false;
  std::uint64_t rebuild_generation_ = 0;
  bool rebuild_adapting_ = false;  // history generation the running rebuild job is for
  std::string loading_path_;
  std::vector<Stroke> pending_strokes_;  // replayed/recovered strokes waiting for the model
  std::optional<Vec3> pending_background_;

  // input state
  bool ui_mouse_ = false, ui_keyboard_ = false;
  double mouse_x_ = 0, mouse_y_ = 0;
  bool left_ = false, right_ = false, middle_ = false;
  enum class Drag { None, Paint, Orbit, Pan, Eyedrop } drag_ = Drag::None;
  Mods mods_;
  bool stroke_open_ = false;
  Stroke current_;
  Vec3 last_dab_ = Vec3::Zero();
  bool have_last_dab_ = false;
  std::optional<Hit> cursor_hit_;
  std::array<int, 4> dirty_{0, 0, -1, -1};
  bool texture_full_upload_ = false, mesh_upload_ = false;
  std::optional<Clock::time_point> first_pending_dab_;
  int frames_since_dab_ = 0;

  // files
  std::vector<std::string> recent_;
  std::optional<std::filesystem::path> pending_recovery_;
  std::optional<std::filesystem::path> pending_screenshot_;
  std::optional<ImageRGBA8> decal_image_;
  std::string decal_path_;
  std::uint64_t saved_version_ = 0;  // history version last written to the recovery file
  std::optional<Clock::time_point> change_time_;

  std::deque<Message> messages_;
  std::vector<std::pair<std::string, double>> last_cycle_;
  std::shared_ptr<const AdaptMaps> maps_;
  std::uint64_t surface_serial_ = 0;
  Stats stats_;
  Clock::time_point last_frame_end_ = Clock::now();
  bool quit_ = false;
};

}  // namespace adaptex::studio
