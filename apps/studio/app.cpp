/// \file app.cpp
/// adaptex-studio application logic (see app.h).
#include "app.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "adaptex/core/errors.h"
#include "adaptex/io/input_file.h"
#include "adaptex/paint/strokes.h"

namespace adaptex::studio {

namespace {
double ms_since(App::Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(App::Clock::now() - t).count();
}
std::string absolute_path(const std::string& p) {
  if (p.rfind("builtin:", 0) == 0) return p;
  std::error_code ec;
  auto a = std::filesystem::absolute(p, ec);
  return ec ? p : a.lexically_normal().string();
}
}  // namespace

// ---- construction ---------------------------------------------------------------------------

App::App(std::unique_ptr<Renderer> renderer, AppOptions options)
    : renderer_(std::move(renderer)),
      options_(std::move(options)),
      store_(options_.config_dir, options_.recovery_dir, options_.autosave_delay,
             [this](const std::string& text, bool error) { add_message(text, error); }) {}

App::~App() {
  // A quit without waiting (signal, scripted run, second close): say which exports were dropped.
  for (const MaterialExport& e : pending_exports_)
    std::cerr << "adaptex-studio: error: the export to " << e.path.string()
              << " was not written: the studio quit before the final layout was ready\n";
  store_.finish(unsaved(), [this] { return snapshot(); });
}

void App::add_message(std::string text, bool error) {
  (error ? std::cerr : std::cout) << "adaptex-studio: " << (error ? "error: " : "") << text << std::endl;
  messages_.push_back({std::move(text), error});
  while (messages_.size() > 20) messages_.pop_front();
}

// ---- unsaved work -----------------------------------------------------------------------------

bool App::unsaved() const {
  if (jobs_.loading() && !pending_.from_project && !pending_.strokes.empty()) return true;
  return store_.unsaved(document_version(), !history().strokes().empty() || layered());
}

Project App::snapshot() const {
  Project p;
  if (jobs_.loading() && !pending_.strokes.empty()) {  // the strokes wait for the model being loaded
    p.mesh_path = jobs_.loading_path();
    p.strokes.strokes = pending_.strokes;
    p.strokes.background = pending_.background.value_or(history().background());
  } else {
    p.mesh_path = mesh_path();
    p.strokes = history().to_file();
  }
  // The project file the strokes belong to (a recovery file names it); one being opened counts.
  p.project_file = store_.project_path().string();
  if (jobs_.loading() && !pending_.reload && !pending_.project_path.empty())
    p.project_file = pending_.project_path.string();
  p.brush = brush_;
  p.view = view_;
  p.session = session_;
  p.unwrap = unwrap();
  // Adapted on request (not after every stroke): to which strokes, so that reopening adapts to them.
  if (jobs_.loading() && !pending_.reload)
    p.adapted_strokes = pending_.adapted_strokes;
  else if (session_.schedule != ReparamSchedule::EachStroke && !painting_.on_initial_layout() && adapted_for_)
    p.adapted_strokes = std::min(*adapted_for_, p.strokes.strokes.size());  // undone strokes are gone
  p.camera = camera_;
  if (jobs_.loading() && !pending_.reload) {
    p.material = pending_.material;
    p.active_layer = pending_.active_layer;
  } else if (material_) {
    p.material = material_->file();
    p.active_layer = material_->active();
  }
  return p;
}

void App::ask_or_do(Confirm c) {
  if (confirm_) return;  // one question at a time: the first request waits for its answer
  if (!unsaved()) return perform(c);
  c.save_path = suggested_project_path();
  confirm_ = std::move(c);
  add_message("unsaved strokes: asking Save / Discard / Cancel", false);
}

void App::perform(const Confirm& c) {
  switch (c.action) {
    case Confirm::Action::Quit:
      // A queued export is written first (finish_exports() quits then); closing again quits now.
      if (exporting() && !quit_after_exports_) {
        quit_after_exports_ = true;
        add_message("finishing the export before quitting (close again to quit without it)", false);
      } else {
        quit_ = true;
      }
      break;
    case Confirm::Action::OpenMesh: open_mesh(c.path); break;
    case Confirm::Action::OpenProject: open_project(c.path); break;
    case Confirm::Action::New: new_scene(); break;
    case Confirm::Action::Recover: recover(c.path); break;
  }
}

void App::request_quit() {
  if (quit_after_exports_) return perform({Confirm::Action::Quit, {}});  // the second close
  ask_or_do({Confirm::Action::Quit, {}});
}
void App::request_open_mesh(const std::string& path) { ask_or_do({Confirm::Action::OpenMesh, path}); }
void App::request_open_project(const std::filesystem::path& path) {
  ask_or_do({Confirm::Action::OpenProject, path.string()});
}
void App::request_new() { ask_or_do({Confirm::Action::New, {}}); }

void App::request_open_file(const std::filesystem::path& p) {
  std::string ext = p.extension().string();  // any case: PHOTO.JPG is an image
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  if (ext == ".adaptex") return request_open_project(p);
  if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") return load_decal(p);
  if (ext != ".json") return request_open_mesh(p.string());
  // A project or a stroke file, read once (regular files only, bounded size: a dropped FIFO or
  // directory is an error, not a hang). Every error message names the file.
  try {
    const std::string text = read_input_file(p);
    const auto j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_object() && j.value("format", "") == "adaptex.studio-project") {
      request_open_project(p);
    } else if (AnyStrokeFile any = parse_any_strokes(text, p.string(), p.parent_path()); any.index() == 0) {
      replay(std::get<StrokeFile>(any));
      add_message("replaying " + p.string(), false);
    } else {
      open_material(std::get<MaterialStrokeFile>(std::move(any)));
      add_message("opened the layered material " + p.string(), false);
    }
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

bool App::confirm_save(const std::filesystem::path& path) {
  if (!confirm_ || !save_project(path)) return false;
  const Confirm c = *confirm_;
  confirm_.reset();
  perform(c);
  return true;
}

void App::confirm_discard() {
  if (!confirm_) return;
  store_.discard(document_version());
  pending_ = PendingLoad();
  const Confirm c = *confirm_;
  confirm_.reset();
  add_message("discarded the unsaved strokes", false);
  perform(c);
}

void App::confirm_cancel() {
  if (!confirm_) return;
  confirm_.reset();
  add_message("cancelled: the unsaved strokes are kept", false);
}

// ---- files ------------------------------------------------------------------------------------

void App::open_mesh(const std::string& path_in) {
  if (pending_.reload) pending_ = PendingLoad();  // another mesh replaces the running re-unwrap
  const std::string path = absolute_path(path_in);
  const Vec3 bg = pending_.background.value_or(history().background());
  // A project or recovery file (pending_.unwrap set) keeps its own texture size.
  const bool fresh = !pending_.unwrap.has_value() && !pending_.reload;
  jobs_.start_load(path, session_, bg, LoadRequest{pending_.unwrap.value_or(unwrap_), fresh && size_from_texture_});
  if (path.rfind("builtin:", 0) != 0) note_folder(path);
  // A recovery file of this mesh or project (kept for later, or another one) is asked about first.
  store_.recovery().reoffer(path, pending_.project_path);
}

void App::cancel_load() { jobs_.cancel_load(); }

void App::new_scene() {
  jobs_.cancel_load();
  pending_ = PendingLoad();
  painting_.clear();
  material_.reset();
  jobs_.stop_material();
  store_.mark_clean(document_version(), {});
  last_cycle_.clear();
  maps_.reset();
  atlas_state_.clear();
  comparison_.reset();
  adapt_pending_ = false;
}

void App::replay(const StrokeFile& file) {
  if (material_) {  // onto the active layer
    edit_material([&](MaterialDocument& d) {
      for (MaterialStroke& m : material_from_v1(file).layers.front().strokes) d.add_stroke(std::move(m));
    });
    return;
  }
  if (!has_model() || (jobs_.loading() && !pending_.reload)) {  // a re-unwrap keeps the live history
    pending_.strokes.insert(pending_.strokes.end(), file.strokes.begin(), file.strokes.end());
    pending_.background = file.background;
    pending_.from_project = false;
    return;
  }
  std::vector<Stroke> all = history().strokes();
  all.insert(all.end(), file.strokes.begin(), file.strokes.end());
  painting_.history().reset(std::move(all), history().strokes().empty() ? file.background : history().background());
  history_changed();
}

void App::add_stroke(Stroke stroke) {
  if (!painting_.surface() || painting_.stroke_open()) throw Error("add_stroke: no model, or a stroke is open");
  validate_stroke(stroke, "added stroke");
  record_stroke(std::move(stroke));
}

void App::apply_project(Project p, bool from_project, const std::filesystem::path& project_path) {
  brush_ = p.brush;
  view_ = p.view;
  session_ = p.session;
  pending_ = PendingLoad{std::move(p.strokes.strokes), p.strokes.background, from_project, project_path, false,
                         p.camera};
  pending_.unwrap = p.unwrap;
  pending_.adapted_strokes = p.adapted_strokes;
  pending_.material = std::move(p.material);
  pending_.active_layer = p.active_layer;
  open_mesh(p.mesh_path);
}

void App::open_project(const std::filesystem::path& path) {
  try {
    const auto file = std::filesystem::absolute(path).lexically_normal();
    apply_project(read_project(path), true, file);
    note_folder(file);
    add_message("opened project " + path.string(), false);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

bool App::save_project(const std::filesystem::path& path) {
  // Strokes waiting for their model (a recovered or replayed session still loading) are work too.
  const bool waiting = jobs_.loading() && !pending_.reload && !pending_.strokes.empty();
  if (!has_model() && !waiting) {
    add_message("nothing to save: open a mesh first", true);
    return false;
  }
  const auto file = std::filesystem::absolute(path).lexically_normal();
  if (!store_.save(file, snapshot(), document_version())) return false;
  note_folder(file);
  if (waiting) {  // once loaded, they are what the file holds
    pending_.from_project = true;
    pending_.project_path = file;
  }
  return true;
}

bool App::save() {
  if (store_.project_path().empty()) {
    add_message("no project file yet: type a path under File > Project and press Save As", true);
    return false;
  }
  return save_project(store_.project_path());
}

void App::note_folder(const std::filesystem::path& file) {
  store_.set_last_folder(std::filesystem::absolute(file).lexically_normal().parent_path());
}

std::filesystem::path App::last_folder() const {
  std::error_code ec;
  if (const auto& f = store_.last_folder(); !f.empty() && std::filesystem::is_directory(f, ec)) return f;
  if (const std::string m = mesh_path(); !m.empty() && m.rfind("builtin:", 0) != 0)
    return std::filesystem::path(m).parent_path();
  return std::filesystem::current_path(ec);
}

std::filesystem::path App::suggested_path(FileKind kind) const {
  std::string stem = has_model() ? std::filesystem::path(mesh_path()).stem().string() : "";
  if (stem.rfind("builtin:", 0) == 0) stem = stem.substr(8);
  if (stem.empty()) stem = "untitled";
  switch (kind) {
    case FileKind::SaveProject:
      return store_.project_path().empty() ? last_folder() / (stem + ".adaptex") : store_.project_path();
    case FileKind::ExportGlb: return last_folder() / (stem + ".glb");
    case FileKind::Screenshot: return last_folder() / (stem + ".png");
    case FileKind::SaveBrushPreset: return last_folder() / "brush.json";
    default: return last_folder();
  }
}

// ---- recovery ---------------------------------------------------------------------------------

void App::recover_at_start() {
  RecoveryFiles& r = store_.recovery();
  if (options_.recover == RecoverMode::Ask) return;
  if (options_.recover == RecoverMode::Yes && r.next_offer()) recover(r.next_offer()->file);
  for (const RecoveryOffer& o : r.leave_all())
    std::cerr << "adaptex-studio: recovery file " << o.file.string() << " left untouched (--recover "
              << (options_.recover == RecoverMode::No ? "no" : "yes: not the newest") << "): "
              << "unsaved: " << strokes_text(o.project.strokes.strokes.size()) << " on " << recovery_owner(o.project)
              << std::endl;
}

void App::accept_recovery() {
  if (const RecoveryOffer* o = recovery_offer()) ask_or_do({Confirm::Action::Recover, o->file.string()});
}

void App::recover(const std::filesystem::path& file) {
  try {
    Project p = store_.recovery().take(file);
    const size_t n = p.strokes.strokes.size();
    const std::string owner = recovery_owner(p);
    const std::filesystem::path project = p.project_file;
    apply_project(std::move(p), false, project);
    pending_.recovered = true;
    add_message("recovered " + strokes_text(n) + " on " + owner, false);
  } catch (const std::exception& e) {
    add_message(std::string("recovery failed: ") + e.what(), true);
  }
}

void App::discard_recovery() {
  const RecoveryOffer* o = recovery_offer();
  if (!o) return;
  const std::string file = o->file.string();
  store_.recovery().discard(o->file);
  add_message("discarded the recovery file " + file, false);
}

void App::defer_recovery() {
  const RecoveryOffer* o = recovery_offer();
  if (!o) return;
  const std::string file = o->file.string();
  store_.recovery().defer(o->file);
  add_message("kept the recovery file " + file + " for later", false);
}

std::string App::current_file() const {
  if (!store_.project_path().empty()) return store_.project_path().string();
  if (jobs_.loading() && !pending_.reload)
    return pending_.project_path.empty() ? jobs_.loading_path() : pending_.project_path.string();
  return mesh_path();
}

// ---- queries ----------------------------------------------------------------------------------

std::string App::mesh_path() const { return has_model() ? painting_.model()->path : std::string(); }
const TriMesh* App::mesh() const { return painting_.surface() ? painting_.surface()->mesh.get() : nullptr; }
const Parameterization* App::param() const {
  return painting_.surface() ? painting_.surface()->param.get() : nullptr;
}
const ImageRGBA8* App::texture() const {
  return painting_.surface() ? &painting_.surface()->canvas->texture() : nullptr;
}

double App::diagonal() const {
  const double diag = has_model() ? painting_.model()->box.diagonal() : 1.0;
  return diag > 0 ? diag : 1.0;
}

Vec3 App::brush_anchor() const { return cursor_hit_ ? cursor_hit_->point : camera_.target; }

double App::world_radius() const { return brush_world_radius(brush_, camera_, brush_anchor(), diagonal()); }

std::vector<ScreenCircle> App::brush_cursors() const {
  if (resize_) return {{resize_->centre, resize_->pixels}};
  if (!cursor_hit_ || input_.ui_mouse() || brush_.tool == Tool::Eyedropper || !has_model()) return {};
  const Drag d = input_.drag();
  if (d != Drag::None && d != Drag::Paint) return {};
  std::vector<ScreenCircle> out;
  // Centred on the cursor; the world radius (the stroke's) shown at each circle's own depth.
  const double r = world_radius();
  out.push_back({Vec2(input_.x(), input_.y()), r / camera_.pixel_size_at(cursor_hit_->point)});
  if (brush_.symmetry_axis >= 0) {
    const Ray ray = camera_.pixel_ray(input_.x(), input_.y());
    if (auto mh = painting_.mirror_hit(ray, *cursor_hit_, brush_.symmetry_axis)) {
      const Vec3 s = camera_.project(mh->point);
      if (s.z() < 1) out.push_back({Vec2(s.x(), s.y()), r / camera_.pixel_size_at(mh->point)});
    }
  }
  return out;
}

bool App::adapt_wanted() const {
  if (!adapt_pending_ || !painting_.surface()) return false;
  // With nothing to adapt to, the layout is the initial one (paint_history keeps it).
  const bool keeps_initial = adapt_mode() == AdaptMode::None || history().strokes().empty();
  return !(keeps_initial && painting_.on_initial_layout());
}

bool App::idle() const {
  if (jobs_.busy() || !pending_.strokes.empty() || exporting()) return false;
  if (!painting_.surface()) return true;
  if (material_) return material_settled();
  return painting_.in_sync() && !painting_.stale(session_.texture_size) && !adapt_wanted();
}

std::optional<std::pair<std::string, double>> App::progress() const {
  auto p = jobs_.progress();
  if (!exporting()) return p;
  // The export waits for the settle: its progress (nothing yet: the strokes are composited first).
  if (p) return std::make_pair("Exporting... waiting for the final layout: " + p->first, p->second);
  return std::make_pair(std::string("Exporting... waiting for the final layout"), 0.0);
}

bool App::wait_idle(double timeout_seconds) {
  const auto t0 = Clock::now();
  while (true) {
    settle_adaptation_now();  // a script wants the settled layout now, not after the pause
    begin_frame();
    if (idle()) return true;
    if (std::chrono::duration<double>(Clock::now() - t0).count() > timeout_seconds) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

std::optional<Hit> App::pick(double x, double y) const { return painting_.pick(camera_.pixel_ray(x, y)); }

std::string App::status_line() const {
  std::string s;
  if (has_model()) {
    const Model& m = *painting_.model();
    s += std::filesystem::path(m.path).filename().string() + ": " + std::to_string(m.mesh->num_faces()) + " faces";
    if (const Surface* sf = painting_.surface()) {
      if (sf->mesh->num_faces() != m.mesh->num_faces())
        s += " (refined to " + std::to_string(sf->mesh->num_faces()) + ")";
      s += ", " + std::to_string(sf->param->num_charts) + " charts, texture " + std::to_string(sf->size) + "^2";
    }
    s += " | " + m.layout;
    if (material_)
      s += " | " + std::to_string(material_->num_layers()) + " layers, " + std::to_string(material_->num_strokes()) +
           " strokes, " + std::to_string(material_->file().num_dabs()) + " dabs";
    else
      s += " | " + std::to_string(history().strokes().size()) + " strokes, " + std::to_string(history().num_dabs()) +
           " dabs";
    if (unsaved()) s += " (unsaved)";
  } else {
    s += "no model (drop a mesh file on the window or use Open)";
  }
  s += " | adapt ";
  s += on_artist_atlas() && session_.adapt.mode != AdaptMode::None ? "the atlas" : to_string(session_.adapt.mode);
  if (on_artist_atlas() && !atlas_state_.empty()) s += " (" + atlas_state_ + ")";
  if (view_.fixed_layout) s += showing_fixed_layout() ? " | showing the FIXED layout (L)" : " | fixed layout: painting...";
  if (!last_cycle_.empty()) {
    s += " | last cycle:";
    char buf[64];
    for (const auto& [name, ms] : last_cycle_) {
      std::snprintf(buf, sizeof buf, " %s %.1f ms", name.c_str(), ms);
      s += buf;
    }
  }
  return s;
}

// ---- input ------------------------------------------------------------------------------------

void App::on_resize(int width, int height) {
  camera_.width = std::max(1, width);
  camera_.height = std::max(1, height);
}

void App::on_mouse_button(MouseButton b, bool pressed, Mods mods) {
  if (resize_) {  // an F resize: a left click keeps it, a right click cancels it (as Blender)
    if (pressed && b == MouseButton::Left) end_resize(true);
    if (pressed && b == MouseButton::Right) end_resize(false);
    return;
  }
  if (!pressed) {
    if (input_.release(b, mods) == Drag::Paint) end_paint();
    return;
  }
  switch (input_.press(b, mods, brush_.tool, stencil_.has_value())) {
    case Drag::Paint: begin_paint(); break;
    case Drag::Eyedrop: eyedrop(input_.x(), input_.y()); break;
    default: break;
  }
}

void App::on_cursor(double x, double y) {
  const double x0 = input_.x(), y0 = input_.y();
  const auto [dx, dy] = input_.move(x, y);
  switch (input_.drag()) {
    case Drag::Orbit: camera_.orbit(dx, dy); break;
    case Drag::Pan: camera_.pan(dx, dy); break;
    case Drag::Paint: continue_paint(x0, y0, x, y); break;
    case Drag::Eyedrop: eyedrop(x, y); break;
    case Drag::Stencil: edit_stencil(*stencil_, input_.stencil_edit(), x0, y0, x, y); break;
    case Drag::None: break;
  }
  if (resize_) update_brush_resize(*resize_, brush_, camera_, diagonal(), x, y);
  update_cursor();
}

void App::on_scroll(double steps) {
  if (input_.ui_mouse()) return;
  // Towards the surface point under the cursor (else the point at the target's depth), which stays
  // under the cursor, as Blender's and Substance's "zoom to mouse position".
  const auto hit = pick(input_.x(), input_.y());
  camera_.zoom_towards(steps, hit ? hit->point : camera_.point_at_target_depth(input_.x(), input_.y()));
  update_cursor();
}

void App::on_key(int key, bool pressed, Mods mods) {
  input_.set_mods(mods);
  if (!pressed) return;
  if (confirm_) {
    if (!input_.ui_text()) answer_key(key);
    return;
  }
  if (recovery_offer()) {
    if (!input_.ui_text()) answer_recovery_key(key);
    return;
  }
  if (resize_) {
    if (key == keys::Escape) end_resize(false);
    if (key == 'F' || key == keys::Enter || key == keys::KeypadEnter) end_resize(true);
    return;
  }
  if (input_.ui_keyboard()) return;
  run_command(key_command(key, mods));
  update_cursor();
}

void App::answer_key(int key) {
  if (key == keys::Escape) confirm_cancel();
  if (key == 'D') confirm_discard();
  if (key == 'S') confirm_save(confirm_->save_path);
}

void App::answer_recovery_key(int key) {
  if (key == keys::Escape) defer_recovery();
  if (key == 'D') discard_recovery();
  if (key == 'R') accept_recovery();
}

void App::run_command(Command c) {
  switch (c) {
    case Command::Undo: undo(); break;
    case Command::Redo: redo(); break;
    case Command::Quit: request_quit(); break;
    case Command::Save: save(); break;
    case Command::Frame: frame_model(); break;
    case Command::SmallerBrush: scale_brush(brush_, 1 / 1.15); break;
    case Command::LargerBrush: scale_brush(brush_, 1.15); break;
    case Command::ResizeBrush: start_resize(); break;
    case Command::ProjectStencil: project_decal(decal_opacity_); break;
    case Command::Checker: view_.checker = !view_.checker; break;
    case Command::PbrPreview: view_.pbr = !view_.pbr; break;
    case Command::FixedLayout: toggle_fixed_layout(); break;
    case Command::Help: view_.show_help = !view_.show_help; break;
    case Command::OpenMeshDialog: open_dialog_requested_ = true; break;
    case Command::Brush: brush_.tool = Tool::Brush; break;
    case Command::Eraser: brush_.tool = brush_.tool == Tool::Eraser ? Tool::Brush : Tool::Eraser; break;
    case Command::Eyedropper: brush_.tool = Tool::Eyedropper; break;
    case Command::Wireframe: view_.wireframe = !view_.wireframe; break;
    case Command::None: break;
  }
}

void App::on_drop(const std::vector<std::string>& paths) {
  if (!paths.empty()) request_open_file(paths.front());
}

void App::frame_model() {
  if (has_model()) camera_.frame(painting_.model()->box);
}

// ---- painting ---------------------------------------------------------------------------------

void App::history_changed() {
  if (session_.schedule == ReparamSchedule::EachStroke) adapt_pending_ = true;
}

Stroke App::brush_style() const {
  Stroke s;
  s.type = Stroke::Type::Brush;
  s.color = brush_.tool == Tool::Eraser ? history().background() : brush_.color;
  s.radius = world_radius();
  s.hardness = brush_.hardness;
  s.opacity = brush_.opacity;
  // Layered: the canvas previews the base colour until the composite arrives (nothing for a hidden
  // layer or a brush without base colour).
  if (material_ && (!(brush_.channels & channel_bit(Channel::BaseColor)) || painting_mask() ||
                    !material_->file().layers[material_->active()].visible))
    s.opacity = 0;
  return s;
}

void App::begin_paint() {
  if (!painting_.surface() || painting_.stroke_open()) return;
  const bool pressure_curves = !brush_.radius_curve.points.empty() || !brush_.opacity_curve.points.empty();
  if (!material_ && (brush_.channels != channel_bit(Channel::BaseColor) || pressure_curves) &&
      !edit_material([](MaterialDocument&) {}))
    return;  // another channel than base colour, or pressure curves: the document becomes a layered material
  const bool stamp = brush_.stamp && decal_image_ && brush_.tool == Tool::Brush;
  if (brush_.channels == 0 && (stamp || !painting_mask()))  // a stamp paints the layer's channels, not its mask
    return add_message("the brush paints no channel: choose one in the Brush panel", true);
  if (stamp) return stamp_decal();
  painting_.catch_up();  // paints redone strokes first, so canvas order == history order
  view_.fixed_layout = false;  // paint on (and look at) the adaptive layout
  const auto h = pick(input_.x(), input_.y());
  if (h) cursor_hit_ = h;  // a screen-space radius is taken at the depth of the first dab
  painting_.begin_stroke(brush_style());
  stroke_pressure_.clear();
  if (h) paint_dab_at(*h, camera_.pixel_ray(input_.x(), input_.y()));
}

void App::continue_paint(double x0, double y0, double x1, double y1) {
  if (!painting_.stroke_open()) return;
  const int n = std::max(1, int(std::ceil(std::hypot(x1 - x0, y1 - y0))));  // one ray per pixel of travel
  const double step = std::max(1e-12, brush_.spacing) * painting_.open_stroke().radius;
  for (int k = 1; k <= n; ++k) {
    const double t = double(k) / n;
    const double px = x0 + (x1 - x0) * t, py = y0 + (y1 - y0) * t;
    auto h = pick(px, py);
    if (!h) continue;
    if (const auto last = painting_.last_dab(); last && (h->point - *last).norm() < step) continue;
    paint_dab_at(*h, camera_.pixel_ray(px, py));
  }
}

void App::paint_dab_at(const Hit& h, const Ray& ray) {
  const auto t0 = Clock::now();
  painting_.add_dab(h, ray, brush_.symmetry_axis);
  stroke_pressure_.resize(painting_.open_stroke().dabs.size(), pen_pressure_);  // a mirrored dab too
  stats_.dab_paint_ms.push_back(ms_since(t0));
  if (!first_pending_dab_) {
    first_pending_dab_ = t0;
    frames_since_dab_ = 0;
  }
}

void App::end_paint() {
  if (material_) {
    Stroke s = painting_.take_stroke();
    if (!s.dabs.empty()) record_stroke(std::move(s));
    return;
  }
  if (!painting_.end_stroke()) return;
  store_.autosave_soon();
  history_changed();
}

void App::eyedrop(double x, double y) {
  const auto h = pick(x, y);
  if (h && material_)
    pick_channels(*h);
  else if (h)
    brush_.color = sample_colour(*h);
}

void App::start_resize() {
  if (!has_model() || input_.drag() != Drag::None || input_.ui_mouse()) return;
  resize_ = begin_brush_resize(brush_, camera_, brush_anchor(), diagonal(), input_.x(), input_.y());
}

void App::end_resize(bool keep) {
  if (!keep && resize_) brush_ = resize_->before;
  resize_.reset();
}

void App::update_cursor() {
  const Drag d = input_.drag();
  cursor_hit_ = (d == Drag::None || d == Drag::Paint) ? pick(input_.x(), input_.y()) : std::nullopt;
}

void App::undo() {
  if (material_) {
    if (!painting_.stroke_open() && material_->undo()) material_changed();
    return;
  }
  if (painting_.undo()) history_changed();
}

void App::redo() {
  if (material_) {
    if (!painting_.stroke_open() && material_->redo()) material_changed();
    return;
  }
  if (painting_.redo()) history_changed();
}

void App::set_background_colour(const Vec3& bg) {
  if (bg == history().background()) return;
  if (material_) return add_message("a layered material keeps its background (paint a fill layer instead)", true);
  painting_.history().set_background(bg);
  history_changed();
}

// ---- decals -----------------------------------------------------------------------------------

void App::load_decal(const std::filesystem::path& path) {
  try {
    decal_image_ = load_image(path);
    decal_path_ = std::filesystem::absolute(path).lexically_normal().string();
    note_folder(path);
    stencil_ = fit_stencil(camera_, double(decal_image_->width) / std::max(1, decal_image_->height));
    add_message("decal image " + path.string() +
                    " loaded as a stencil: right drag moves it, Shift scales, Ctrl rotates; P projects it",
                false);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::project_decal(double opacity) {
  if (!decal_image_ || !painting_.surface() || painting_.stroke_open()) return;
  record_decal(stencil_ ? stencil_->decal_camera(camera_) : camera_.decal_camera(), opacity);
  add_message(stencil_ ? "projected the stencil" : "projected the decal from the view", false);
}

void App::record_decal(const DecalCamera& camera, double opacity, unsigned channels) {
  Stroke s;
  s.type = Stroke::Type::Decal;
  s.image = *decal_image_;
  s.image_path = decal_path_;
  s.opacity = opacity;
  s.camera = camera;
  if (material_) return record_material_stroke(material_decal_stroke(std::move(s), channels));
  record_stroke(std::move(s));  // a single base-colour layer: the image's colour
}

void App::stamp_decal() {
  const auto h = pick(input_.x(), input_.y());
  if (!h) return;
  // The stencil's projection, centred at the cursor and as tall as the brush's diameter there.
  Stencil st = fit_stencil(camera_, double(decal_image_->width) / decal_image_->height);
  if (stencil_) st.angle = stencil_->angle;
  st.centre = Vec2(input_.x(), input_.y());
  st.height = 2 * brush_screen_radius(brush_, camera_, h->point, diagonal());
  record_decal(st.decal_camera(camera_), brush_.opacity, brush_.channels);
}

void App::clear_decal() {
  decal_image_.reset();
  decal_path_.clear();
  stencil_.reset();
  if (input_.drag() == Drag::Stencil) input_.release(MouseButton::Right, input_.mods());
}

// ---- background jobs --------------------------------------------------------------------------

void App::request_adapt() {
  if (session_.adapt.mode == AdaptMode::None) return add_message("choose an adaptation mode first", true);
  adapt_pending_ = true;
  adapt_prefix_.reset();
}

void App::session_options_changed() { history_changed(); }

void App::cancel_adaptation() {
  if (!jobs_.rebuild_adapting()) return;
  jobs_.cancel_rebuild();
  adapt_pending_ = false;
  add_message("adaptation cancelled: the layout stays until the next stroke (or Re-parameterize now)", false);
}

AdaptMode App::adapt_mode() const { return session_.adapt.mode; }

std::string App::atlas_adaptation() const {
  if (!on_artist_atlas() || session_.adapt.mode == AdaptMode::None) return {};
  std::string what = "on the artist's UV atlas, adaptation keeps its charts, seams and mirror images";
  if (painting_.model()->shared_fraction > 0) what += ", and the texels its overlapping charts share";
  return what + ", and moves texels to the painted detail only where that reconstructs the painting better "
                "(adaptex shrink; the mode's own settings do not apply; File > Fresh unwrap adapts a fresh layout)";
}

void App::set_unwrap(bool unwrap) {
  unwrap_ = unwrap;
  const auto& m = painting_.model();
  if (!m || m->unwrap_asked == unwrap || m->path.rfind("builtin:", 0) == 0 || jobs_.loading()) return;
  // Reopens the model with the other layout; the strokes are 3-D and go onto it as they are.
  pending_ = PendingLoad{{}, history().background(), !unsaved(), store_.project_path(), true};
  pending_.relayout = true;
  jobs_.start_load(m->path, session_, history().background(), LoadRequest{unwrap_, !unwrap_});
}

void App::request_compare() {
  if (material_) return add_message("the fixed-vs-adaptive comparison is for a single base-colour layer", true);
  if (const Surface* s = painting_.surface()) {
    jobs_.start_compare(*s, history().to_file());
    compare_version_ = history().version();
  }
}

void App::toggle_fixed_layout() {
  if (material_) return add_message("the fixed layout view is for a single base-colour layer", true);
  view_.fixed_layout = !view_.fixed_layout;
  if (!view_.fixed_layout || !has_model()) return;
  if ((!comparison_ || compare_version_ != history().version()) && !jobs_.comparing()) request_compare();
  add_message("fixed layout at the same texture size (L returns to the adaptive one)", false);
}

void App::upload_view() {
  const Comparison* c = comparison_.get();
  const bool fixed = view_.fixed_layout && c && has_model() && compare_version_ == history().version() &&
                     !jobs_.comparing() && c->fixed_param->num_wedges() > 0;
  if (!fixed) {
    if (shown_fixed_) painting_.invalidate_uploads();
    shown_fixed_ = nullptr;
    return painting_.upload(*renderer_);
  }
  if (shown_fixed_.get() == c) return;
  renderer_->set_mesh(*painting_.model()->mesh, *c->fixed_param, nullptr);
  renderer_->set_texture(c->fixed_texture);
  shown_fixed_ = comparison_;
}

void App::start_rebuild(bool adapt) {
  if (jobs_.rebuild_adapting() && !adapt) adapt_pending_ = true;  // the cancelled adaptation runs later
  if (adapt) adapt_pending_ = false;
  StrokeFile file = history().to_file();
  if (adapt && adapt_prefix_) file.strokes.resize(std::min(file.strokes.size(), *std::exchange(adapt_prefix_, {})));
  jobs_.start_rebuild(*painting_.surface(), history().generation(), std::move(file), session_, adapt);
}

void App::maybe_start_rebuild() {
  if (!painting_.surface() || jobs_.loading() || maybe_start_material()) return;
  if (jobs_.rebuilding()) {
    // A rebuild for an older history generation (undo / redo meanwhile) is abandoned, not awaited.
    if (jobs_.rebuild_generation() != history().generation()) start_rebuild(false);
    return;
  }
  if (painting_.stale(session_.texture_size)) {
    jobs_.stop_live();                // its history was rewritten
    return start_rebuild(false);      // quick replay first
  }
  painting_.catch_up();  // pure appends (redo, decals): painted onto the current canvas
  if (!adapt_wanted()) return;
  if (adapts_live()) {
    // The live session paints the new strokes and adapts to them in the background: the
    // cost per stroke does not grow with the history, unlike a rebuild from the initial layout.
    jobs_.feed_live(painting_.model(), history().generation(), history().strokes(), history().background(), session_);
    adapt_pending_ = false;
    return;
  }
  jobs_.stop_live();
  if (!painting_.stroke_open()) start_rebuild(true);
}

bool App::adapts_live() const {
  return session_.schedule == ReparamSchedule::EachStroke && adapt_mode() != AdaptMode::None && !on_artist_atlas() &&
         !history().strokes().empty() && !material_;
}

void App::maybe_unwrap_again() {
  const auto& m = painting_.model();
  if (!m || jobs_.loading() || (m->unwrap_size == session_.texture_size && m->unwrap_padding == session_.padding))
    return;
  // `adaptex paint --size N` unwraps with a gutter of so many texels of N: so does the studio.
  pending_ = PendingLoad{{}, history().background(), !unsaved(), store_.project_path(), true};
  jobs_.start_load(m->path, session_, history().background(), LoadRequest{m->unwrap_asked, false});
}

void App::finish_load(Job<LoadResult>& job) {
  PendingLoad pending = std::exchange(pending_, PendingLoad());
  try {
    LoadResult r = job.take();
    if (painting_.stroke_open()) end_paint();
    // A reload keeps the history as it is now (strokes painted while it ran included).
    std::vector<Stroke> strokes = pending.reload ? history().strokes() : std::move(pending.strokes);
    const Vec3 bg = pending.reload ? history().background() : pending.background.value_or(history().background());
    const auto model = r.model;
    if (model->base) session_.texture_size = model->unwrap_size;  // it may have brought its texture's size
    painting_.set_model(model, std::move(r.surface), std::move(strokes), bg);
    jobs_.stop_material();
    ++material_generation_;
    if (!pending.reload) {
      material_.reset();
      if (pending.material) {
        material_.emplace(std::move(*pending.material));
        if (pending.active_layer >= 0 && pending.active_layer < material_->num_layers())
          material_->set_active(pending.active_layer);
      }
    }
    // Strokes from a project are saved; replayed or recovered ones are not.
    const bool saved = pending.from_project || (history().strokes().empty() && !material_ && !pending.recovered);
    store_.mark_clean(saved ? document_version() : ~0ull, pending.project_path);
    last_cycle_.clear();
    maps_.reset();
    atlas_state_.clear();
    comparison_.reset();
    adapted_for_.reset();
    adapt_prefix_.reset();
    history_changed();
    // A project adapted on request: adapted again to the same strokes (the rest painted on top).
    if (pending.adapted_strokes && session_.schedule != ReparamSchedule::EachStroke && !pending.reload) {
      adapt_prefix_ = pending.adapted_strokes;
      adapt_pending_ = true;
    }
    if (pending.relayout) return add_message("reopened on the " + model->layout, false);
    if (pending.reload)
      return add_message("unwrapped again for a " + std::to_string(model->unwrap_size) + "^2 texture", false);
    // From the front (+Z, the glTF and Stanford convention), whatever the last model's view was.
    camera_.yaw = 0;
    camera_.pitch = 0;
    camera_.frame(model->box);  // sets the clip planes' scene radius
    if (pending.camera) {         // the project's view
      camera_.target = pending.camera->target;
      camera_.distance = pending.camera->distance;
      camera_.yaw = pending.camera->yaw;
      camera_.pitch = pending.camera->pitch;
      camera_.fov_y_degrees = pending.camera->fov_y_degrees;
      camera_.orbit(0, 0);  // keeps the pitch in the camera's range
    }
    store_.add_recent(model->path);
    char buf[64];
    std::snprintf(buf, sizeof buf, " in %.2f s", r.seconds);
    add_message("loaded " + model->path + buf + ", painting on its " + model->layout, false);
    if (const std::string note = atlas_adaptation(); !note.empty()) add_message(note, false);
  } catch (const std::exception& e) {
    const bool cancelled = dynamic_cast<const CancelledError*>(&e) != nullptr;
    add_message(cancelled ? "loading cancelled" : e.what(), !cancelled);
    if (pending.reload && has_model()) {  // keep the layout's texture size (else it would unwrap again)
      session_.texture_size = painting_.model()->unwrap_size;
      session_.padding = painting_.model()->unwrap_padding;
    }
  }
}

void App::finish_rebuild(Job<RebuildResult>& job) {
  try {
    RebuildResult r = job.take();
    auto maps = std::move(r.maps);
    auto phases = std::move(r.phase_ms);
    const std::string note = std::move(r.note);
    const size_t painted = r.surface->painted;
    if (painting_.accept_rebuilt(std::move(r.surface), session_.texture_size) && maps) {
      adapted_for_ = painting_.on_initial_layout() ? std::nullopt : std::optional<size_t>(painted);
      last_cycle_ = std::move(phases);
      maps_ = std::move(maps);
      if (!note.empty()) {
        atlas_state_ = maps_->accepted ? "adapted" : "kept as it was";
        add_message(note, false);
      }
    }
  } catch (const CancelledError&) {
  } catch (const std::exception& e) {
    add_message(e.what(), true);
    adapt_pending_ = false;
  }
}

void App::finish_live() {
  if (!adapts_live()) return jobs_.stop_live();  // adaptation turned off, or nothing to adapt to
  try {
    std::optional<RebuildResult> r = jobs_.finished_live();
    if (!r) return;
    // Options changed since (the next feed starts a session for them): not shown.
    if (!jobs_.live()->serves(painting_.model().get(), history().generation(), session_options_key(session_)))
      return;
    auto maps = std::move(r->maps);
    auto phases = std::move(r->phase_ms);
    if (painting_.accept_rebuilt(std::move(r->surface), session_.texture_size)) {
      last_cycle_ = std::move(phases);
      if (maps) maps_ = std::move(maps);
    }
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::poll_jobs() {
  jobs_.reap();
  if (auto job = jobs_.finished_compare()) {
    try {
      comparison_ = std::make_shared<Comparison>(job->take());
    } catch (const std::exception& e) {
      add_message(std::string("comparison failed: ") + e.what(), true);
    }
  }
  if (auto job = jobs_.finished_load()) finish_load(*job);
  if (auto job = jobs_.finished_rebuild())
    if (!material_) finish_rebuild(*job);
  finish_live();
  finish_material();
  finish_exports();
  maybe_unwrap_again();
  maybe_start_rebuild();
}

// ---- frame ------------------------------------------------------------------------------------

void App::begin_frame() {
  poll_jobs();
  store_.autosave_tick(document_version(), unsaved() && has_model(), !painting_.stroke_open(),
                       [this] { return snapshot(); });
}

void App::render() {
  upload_view();
  FrameView v;
  v.camera = camera_;
  v.has_mesh = painting_.surface() != nullptr;
  v.wireframe = view_.wireframe;
  v.background = view_.background;
  v.checker = view_.checker;
  v.pbr = view_.pbr;
  renderer_->draw(v);
}

void App::end_frame() {
  if (pending_screenshot_) {
    const auto path = *pending_screenshot_;
    pending_screenshot_.reset();
    try {
      save_png(path, renderer_->read_pixels(camera_.width, camera_.height));
      add_message("screenshot " + path.string(), false);
    } catch (const std::exception& e) {
      add_message(e.what(), true);
    }
  }
  const auto now = Clock::now();
  if (stats_.frame_ms.size() > 100000) stats_ = Stats();  // bounded memory in long sessions
  stats_.frame_ms.push_back(std::chrono::duration<double, std::milli>(now - last_frame_end_).count());
  last_frame_end_ = now;
  if (first_pending_dab_) {
    ++frames_since_dab_;
    stats_.dab_latency_ms.push_back(std::chrono::duration<double, std::milli>(now - *first_pending_dab_).count());
    stats_.dab_latency_frames.push_back(frames_since_dab_);
    first_pending_dab_.reset();
  }
}

// ---- outputs ----------------------------------------------------------------------------------

void App::screenshot(const std::filesystem::path& path) { pending_screenshot_ = path; }

void App::save_history(const std::filesystem::path& path) {
  if (material_) return save_material_strokes(path);
  try {
    save_strokes(path, history().to_file());
    add_message("saved the stroke history to " + path.string(), false);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::save_texture(const std::filesystem::path& path) {
  if (!texture()) return add_message("no texture to save", true);
  try {
    save_png(path, *texture());
    add_message("saved the texture to " + path.string(), false);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::note_export_while_adapting() {
  if (jobs_.live_caught_up() && !jobs_.rebuilding()) return;
  jobs_.settle_live_now();  // the settled layout sooner, for the next export
  add_message("adaptation is still running: exported the layout shown", false);
}

void App::export_obj(const std::filesystem::path& dir) {
  if (!texture()) return add_message("nothing to export", true);
  if (material_) return export_material({false, dir});
  try {
    const std::string name = std::filesystem::path(mesh_path()).stem().string();
    studio::export_obj(dir, name.empty() ? "model" : name, *mesh(), *param(), *texture());
    add_message("exported OBJ+MTL+PNG to " + dir.string(), false);
    note_folder(dir);
    note_export_while_adapting();
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::export_glb(const std::filesystem::path& path) {
  if (!texture()) return add_message("nothing to export", true);
  if (material_) return export_material({true, path});
  try {
    studio::export_glb(path, *mesh(), *param(), *texture());
    add_message("exported " + path.string(), false);
    note_folder(path);
    note_export_while_adapting();
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

}  // namespace adaptex::studio
