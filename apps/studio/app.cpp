/// \file app.cpp
/// adaptex-studio application logic (see app.h).
#include "app.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"

namespace adaptex::studio {

namespace {
double ms_since(App::Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(App::Clock::now() - t).count();
}
void merge_rect(std::array<int, 4>& a, const std::array<int, 4>& b) {
  if (b[2] < b[0]) return;
  if (a[2] < a[0]) {
    a = b;
    return;
  }
  a = {std::min(a[0], b[0]), std::min(a[1], b[1]), std::max(a[2], b[2]), std::max(a[3], b[3])};
}
std::string absolute_path(const std::string& p) {
  if (p.rfind("builtin:", 0) == 0) return p;
  std::error_code ec;
  auto a = std::filesystem::absolute(p, ec);
  return ec ? p : a.lexically_normal().string();
}
}  // namespace

struct App::Model {
  std::string path;
  TriMesh mesh;
  std::shared_ptr<const Parameterization> initial;  // the unwrap() result (the fixed baseline)
  BoundingBox box;
  std::unique_ptr<RayCaster> caster;
};

struct App::Surface {
  std::shared_ptr<const Model> model;
  std::shared_ptr<const Parameterization> param;
  std::uint64_t generation = 0;  // history generation the canvas was built for
  size_t painted = 0;            // history strokes painted into the canvas
  int size = 0;
  std::unique_ptr<Canvas> canvas;  // declared last: destroyed before param / model
};

struct App::LoadResult {
  std::shared_ptr<const Model> model;
  std::unique_ptr<Surface> surface;
  double seconds = 0;
};

struct App::RebuildResult {
  std::unique_ptr<Surface> surface;
  std::vector<std::pair<std::string, double>> phase_ms;
  std::shared_ptr<const AdaptMaps> maps;
  bool adapted = false;
};

// ---- construction ---------------------------------------------------------------------------

App::App(std::unique_ptr<Renderer> renderer, AppOptions options)
    : renderer_(std::move(renderer)), options_(std::move(options)) {
  load_config();
  if (!options_.recovery_dir.empty()) {
    std::error_code ec;
    const auto rec = recovery_path();
    const auto offered = options_.recovery_dir / "recovery.offered.json";
    if (std::filesystem::exists(rec)) std::filesystem::rename(rec, offered, ec);
    if (std::filesystem::exists(offered)) {
      pending_recovery_ = offered;
      std::cout << "adaptex-studio: recovery file found: " << offered.string() << std::endl;
      if (options_.auto_recover) accept_recovery();
    }
  }
}

App::~App() {
  compare_job_.reset();
  if (load_job_) load_job_->cancel();
  if (rebuild_job_) rebuild_job_->cancel();
  autosave_job_.reset();
  // A clean exit removes this session's recovery file (it exists to survive crashes).
  if (!options_.recovery_dir.empty()) {
    std::error_code ec;
    std::filesystem::remove(recovery_path(), ec);
  }
}

std::filesystem::path App::recovery_path() const { return options_.recovery_dir / "recovery.json"; }

void App::add_message(std::string text, bool error) {
  (error ? std::cerr : std::cout) << "adaptex-studio: " << (error ? "error: " : "") << text << std::endl;
  messages_.push_back({std::move(text), error});
  while (messages_.size() > 20) messages_.pop_front();
}

// ---- config (recent files) --------------------------------------------------------------------

void App::load_config() {
  if (options_.config_dir.empty()) return;
  std::ifstream in(options_.config_dir / "studio.json");
  if (!in) return;
  try {
    const auto j = nlohmann::json::parse(in);
    for (const auto& r : j.value("recent", nlohmann::json::array())) recent_.push_back(r.get<std::string>());
  } catch (const std::exception&) {
    add_message("ignoring a corrupt config file " + (options_.config_dir / "studio.json").string(), true);
  }
}

void App::save_config() const {
  if (options_.config_dir.empty()) return;
  try {
    AtomicOutput out;
    const auto tmp = out.add(options_.config_dir / "studio.json");
    {
      std::ofstream o(tmp);
      o << nlohmann::json{{"recent", recent_}}.dump(1) << "\n";
    }
    out.commit();
  } catch (const std::exception&) {
  }
}

void App::add_recent(const std::string& path) {
  recent_.erase(std::remove(recent_.begin(), recent_.end(), path), recent_.end());
  recent_.insert(recent_.begin(), path);
  if (recent_.size() > 10) recent_.resize(10);
  save_config();
}

// ---- loading ----------------------------------------------------------------------------------

void App::open_mesh(const std::string& path_in) {
  const std::string path = absolute_path(path_in);
  if (load_job_) {
    load_job_->cancel();
    retired_jobs_.push_back(std::move(load_job_));  // never wait for it on the UI thread
  }
  loading_path_ = path;
  const int size = adapt_.texture_size;
  const Vec3 bg = pending_background_.value_or(history_.background());
  load_job_ = std::make_unique<Job<LoadResult>>([path, size, bg](Job<LoadResult>& job) {
    const auto t0 = Clock::now();
    job.progress("read", 0.0);
    auto model = std::make_shared<Model>();
    model->path = path;
    model->mesh = load_mesh(path);
    model->box = bounding_box(model->mesh);
    if (!job.progress("index", 0.0)) throw CancelledError();
    model->caster = std::make_unique<RayCaster>(model->mesh);
    auto param = std::make_shared<Parameterization>(
        unwrap_mesh(model->mesh, [&job](std::string_view phase, double f) { return job.progress(phase, f); }));
    if (!job.progress("texture", 0.0)) throw CancelledError();
    model->initial = param;
    LoadResult r;
    r.model = model;
    r.surface = std::make_unique<Surface>();
    r.surface->model = model;
    r.surface->param = param;
    r.surface->size = size;
    r.surface->canvas = std::make_unique<Canvas>(model->mesh, *param, size, size, bg);
    r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    r.model = std::move(model);
    return r;
  });
}

void App::cancel_load() {
  if (load_job_) load_job_->cancel();
}

void App::replay(const StrokeFile& file) {
  if (!model_ || load_job_) {
    pending_strokes_.insert(pending_strokes_.end(), file.strokes.begin(), file.strokes.end());
    pending_background_ = file.background;
    return;
  }
  std::vector<Stroke> all = history_.strokes();
  all.insert(all.end(), file.strokes.begin(), file.strokes.end());
  history_.reset(std::move(all), history_.strokes().empty() ? file.background : history_.background());
}

void App::open_project(const std::filesystem::path& path) {
  try {
    Project p = read_project(path);
    brush_ = p.brush;
    view_ = p.view;
    adapt_ = p.adapt;
    pending_strokes_ = std::move(p.strokes.strokes);
    pending_background_ = p.strokes.background;
    open_mesh(p.mesh_path);
    add_message("opened project " + path.string(), false);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::save_project(const std::filesystem::path& path) {
  try {
    Project p;
    p.mesh_path = mesh_path();
    p.strokes = history_.to_file();
    p.brush = brush_;
    p.view = view_;
    p.adapt = adapt_;
    p.camera = camera_;
    write_project(path, p);
    add_message("saved project " + path.string(), false);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::accept_recovery() {
  if (!pending_recovery_) return;
  const auto path = *pending_recovery_;
  pending_recovery_.reset();
  try {
    Project p = read_project(path);
    brush_ = p.brush;
    view_ = p.view;
    adapt_ = p.adapt;
    const size_t n = p.strokes.strokes.size();
    pending_strokes_ = std::move(p.strokes.strokes);
    pending_background_ = p.strokes.background;
    open_mesh(p.mesh_path);
    add_message("recovered " + std::to_string(n) + " strokes on " + p.mesh_path + " from " + path.string(), false);
  } catch (const std::exception& e) {
    add_message(std::string("recovery failed: ") + e.what(), true);
  }
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

void App::discard_recovery() {
  if (!pending_recovery_) return;
  std::error_code ec;
  std::filesystem::remove(*pending_recovery_, ec);
  pending_recovery_.reset();
}

// ---- queries ----------------------------------------------------------------------------------

std::string App::mesh_path() const { return model_ ? model_->path : std::string(); }
const TriMesh* App::mesh() const { return model_ ? &model_->mesh : nullptr; }
const Parameterization* App::param() const { return surface_ ? surface_->param.get() : nullptr; }
const ImageRGBA8* App::texture() const { return surface_ ? &surface_->canvas->texture() : nullptr; }

double App::world_radius() const {
  const double diag = model_ ? model_->box.diagonal() : 1.0;
  return brush_.radius * (diag > 0 ? diag : 1.0);
}

bool App::idle() const {
  if (load_job_ || rebuild_job_ || compare_job_ || !pending_strokes_.empty()) return false;
  if (!surface_) return true;
  if (surface_->generation != history_.generation() || surface_->painted != history_.strokes().size()) return false;
  if (adapt_pending_ && adapt_.mode != AdaptMode::None) return false;
  return true;
}

bool App::wait_idle(double timeout_seconds) {
  const auto t0 = Clock::now();
  while (true) {
    begin_frame();
    if (idle()) return true;
    if (std::chrono::duration<double>(Clock::now() - t0).count() > timeout_seconds) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

std::optional<Hit> App::pick(double x, double y) const {
  if (!model_) return std::nullopt;
  auto h = model_->caster->intersect(camera_.pixel_ray(x, y));
  if (!h || !h->front_facing) return std::nullopt;
  return h;
}

Vec3 App::sample_colour(const Hit& h) const {
  if (!surface_) return history_.background();
  const Parameterization& p = *surface_->param;
  const Face& uf = p.uv_faces[h.face];
  const Vec2 uv = h.b0 * p.uv[uf[0]] + h.b1 * p.uv[uf[1]] + (1 - h.b0 - h.b1) * p.uv[uf[2]];
  return sample_bilinear(surface_->canvas->texture(), uv.x(), uv.y());
}

std::optional<std::pair<std::string, double>> App::progress() const {
  if (load_job_) return std::make_pair("Loading " + loading_path_ + ": " + load_job_->phase(), load_job_->fraction());
  if (rebuild_job_) return std::make_pair("Updating texture: " + rebuild_job_->phase(), rebuild_job_->fraction());
  return std::nullopt;
}

std::string App::status_line() const {
  std::string s;
  if (model_) {
    s += std::filesystem::path(model_->path).filename().string() + ": " + std::to_string(model_->mesh.num_faces()) +
         " faces";
    if (surface_)
      s += ", " + std::to_string(surface_->param->num_charts) + " charts, texture " + std::to_string(surface_->size) +
           "^2";
    s += " | " + std::to_string(history_.strokes().size()) + " strokes, " + std::to_string(history_.num_dabs()) +
         " dabs";
  } else {
    s += "no model (drop a mesh file on the window or use Open)";
  }
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
  mods_ = mods;
  if (pressed) {
    if (drag_ != Drag::None) return;  // one drag at a time
    if (ui_mouse_) return;            // the UI owns this click
    if (b == MouseButton::Left) {
      left_ = true;
      if (mods.alt) {
        drag_ = Drag::Orbit;
      } else if (brush_.tool == Tool::Eyedropper) {
        drag_ = Drag::Eyedrop;
        eyedrop(mouse_x_, mouse_y_);
      } else {
        drag_ = Drag::Paint;
        begin_paint(mouse_x_, mouse_y_);
      }
    } else if (b == MouseButton::Right) {
      right_ = true;
      drag_ = Drag::Orbit;
    } else {
      middle_ = true;
      drag_ = mods.shift ? Drag::Pan : Drag::Orbit;
    }
  } else {
    if (b == MouseButton::Left) left_ = false;
    if (b == MouseButton::Right) right_ = false;
    if (b == MouseButton::Middle) middle_ = false;
    if (drag_ == Drag::Paint && b == MouseButton::Left) end_paint();
    if (!left_ && !right_ && !middle_) drag_ = Drag::None;
  }
}

void App::on_cursor(double x, double y) {
  const double dx = x - mouse_x_, dy = y - mouse_y_;
  switch (drag_) {
    case Drag::Orbit: camera_.orbit(dx, dy); break;
    case Drag::Pan: camera_.pan(dx, dy); break;
    case Drag::Paint: continue_paint(x, y); break;
    case Drag::Eyedrop: eyedrop(x, y); break;
    case Drag::None: break;
  }
  mouse_x_ = x;
  mouse_y_ = y;
  update_cursor(x, y);
}

void App::on_scroll(double steps) {
  if (ui_mouse_) return;
  camera_.zoom(steps);
  update_cursor(mouse_x_, mouse_y_);
}

void App::on_key(int key, bool pressed, Mods mods) {
  mods_ = mods;
  if (!pressed || ui_keyboard_) return;
  if (mods.ctrl) {
    if (key == 'Z' && mods.shift) redo();
    else if (key == 'Z') undo();
    else if (key == 'Y') redo();
    else if (key == 'Q') request_quit();
    return;
  }
  switch (key) {
    case 'F': frame_model(); break;
    case '[': brush_.radius = std::max(1e-4, brush_.radius / 1.15); break;
    case ']': brush_.radius = std::min(0.5, brush_.radius * 1.15); break;
    case 'B': brush_.tool = Tool::Brush; break;
    case 'E': brush_.tool = brush_.tool == Tool::Eraser ? Tool::Brush : Tool::Eraser; break;
    case 'I': brush_.tool = Tool::Eyedropper; break;
    case 'W': view_.wireframe = !view_.wireframe; break;
    default: break;
  }
  update_cursor(mouse_x_, mouse_y_);
}

void App::on_drop(const std::vector<std::string>& paths) {
  if (paths.empty()) return;
  const std::filesystem::path p = paths.front();
  const std::string ext = p.extension().string();
  if (ext == ".json") {
    // A project or a stroke file.
    try {
      std::ifstream in(p);
      const auto j = nlohmann::json::parse(in);
      if (j.value("format", "") == "adaptex.studio-project") {
        open_project(p);
      } else {
        replay(load_strokes(p));
        add_message("replaying " + p.string(), false);
      }
    } catch (const std::exception& e) {
      add_message(p.string() + ": " + e.what(), true);
    }
  } else if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") {
    load_decal(p);
  } else {
    open_mesh(p.string());
  }
}

void App::frame_model() {
  if (model_) camera_.frame(model_->box);
}

// ---- painting ---------------------------------------------------------------------------------

Stroke App::brush_style() const {
  Stroke s;
  s.type = Stroke::Type::Brush;
  s.color = brush_.tool == Tool::Eraser ? history_.background() : brush_.color;
  s.radius = world_radius();
  s.hardness = brush_.hardness;
  s.opacity = brush_.opacity;
  return s;
}

void App::begin_paint(double x, double y) {
  if (!surface_ || !model_ || stroke_open_) return;
  maybe_start_rebuild();  // paints redone strokes first, so canvas order == history order
  current_ = brush_style();
  stroke_open_ = true;
  have_last_dab_ = false;
  surface_->canvas->begin_stroke(current_);
  if (auto h = pick(x, y)) paint_dab_at(*h, camera_.pixel_ray(x, y));
}

void App::continue_paint(double x, double y) {
  if (!stroke_open_) return;
  const double len = std::hypot(x - mouse_x_, y - mouse_y_);
  const int n = std::max(1, int(std::ceil(len)));  // one ray per pixel of cursor travel
  const double step = std::max(1e-12, brush_.spacing) * current_.radius;
  for (int k = 1; k <= n; ++k) {
    const double t = double(k) / n;
    const double px = mouse_x_ + (x - mouse_x_) * t, py = mouse_y_ + (y - mouse_y_) * t;
    auto h = pick(px, py);
    if (!h) continue;
    if (have_last_dab_ && (h->point - last_dab_).norm() < step) continue;
    paint_dab_at(*h, camera_.pixel_ray(px, py));
  }
}

void App::paint_dab_at(const Hit& h, const Ray& ray) {
  const auto t0 = Clock::now();
  merge_rect(dirty_, surface_->canvas->add_dab(h.point));
  current_.dabs.push_back(h.point);
  last_dab_ = h.point;
  have_last_dab_ = true;
  if (brush_.symmetry_axis >= 0 && model_) {
    const int a = brush_.symmetry_axis;
    const double c = 0.5 * (model_->box.min[a] + model_->box.max[a]);
    Ray m = ray;
    m.origin[a] = 2 * c - m.origin[a];
    m.dir[a] = -m.dir[a];
    auto mh = model_->caster->intersect(m);
    if (mh && mh->front_facing && (mh->point - h.point).norm() > 1e-9 * (1 + model_->box.diagonal())) {
      merge_rect(dirty_, surface_->canvas->add_dab(mh->point));
      current_.dabs.push_back(mh->point);
    }
  }
  stats_.dab_paint_ms.push_back(ms_since(t0));
  if (!first_pending_dab_) {
    first_pending_dab_ = t0;
    frames_since_dab_ = 0;
  }
}

void App::end_paint() {
  if (!stroke_open_) return;
  surface_->canvas->end_stroke();
  stroke_open_ = false;
  if (current_.dabs.empty()) return;
  const bool in_sync = surface_->generation == history_.generation() && surface_->painted == history_.strokes().size();
  history_.push(std::move(current_));
  current_ = Stroke();
  if (in_sync) surface_->painted = history_.strokes().size();
  change_time_ = Clock::time_point{};  // autosave right away
  if (adapt_.mode != AdaptMode::None) adapt_pending_ = true;
}

void App::eyedrop(double x, double y) {
  if (auto h = pick(x, y)) brush_.color = sample_colour(*h);
}

void App::update_cursor(double x, double y) {
  cursor_hit_ = (drag_ == Drag::None || drag_ == Drag::Paint) ? pick(x, y) : std::nullopt;
}

void App::undo() {
  if (stroke_open_) return;
  history_.undo();
}

void App::redo() {
  if (stroke_open_) return;
  history_.redo();
}

void App::set_background_colour(const Vec3& bg) { history_.set_background(bg); }

// ---- decals -----------------------------------------------------------------------------------

void App::load_decal(const std::filesystem::path& path) {
  try {
    decal_image_ = load_image(path);
    decal_path_ = std::filesystem::absolute(path).lexically_normal().string();
    add_message("decal image " + path.string() + " loaded: use Project decal", false);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::project_decal(double opacity) {
  if (!decal_image_ || !surface_ || stroke_open_) return;
  Stroke s;
  s.type = Stroke::Type::Decal;
  s.image = *decal_image_;
  s.image_path = decal_path_;
  s.opacity = opacity;
  s.camera = camera_.decal_camera();
  history_.push(std::move(s));
  change_time_ = Clock::time_point{};
  if (adapt_.mode != AdaptMode::None) adapt_pending_ = true;
}

// ---- background jobs --------------------------------------------------------------------------

void App::start_rebuild(bool adapt) {
  if (rebuild_job_) {
    rebuild_job_->cancel();
    retired_jobs_.push_back(std::move(rebuild_job_));
    if (rebuild_adapting_ && adapt_.mode != AdaptMode::None) adapt_pending_ = true;  // redo it later
  }
  rebuild_adapting_ = adapt;
  auto model = model_;
  auto param = surface_->param;
  const std::uint64_t gen = history_.generation();
  rebuild_generation_ = gen;
  StrokeFile file = history_.to_file();
  const int size = adapt_.texture_size;
  AdaptRequest req;
  req.mode = static_cast<int>(adapt_.mode);  // index into adaptex::adapt_modes()
  req.alpha = adapt_.alpha;
  req.beta = adapt_.beta;
  req.coarse_grid = adapt_.coarse_grid;
  req.fine_grid = adapt_.fine_grid;
  req.texture_size = size;
  if (adapt) adapt_pending_ = false;
  rebuild_job_ = std::make_unique<Job<RebuildResult>>(
      [model, param, gen, file = std::move(file), size, req, adapt](Job<RebuildResult>& job) {
        RebuildResult r;
        const auto t0 = Clock::now();
        auto s = std::make_unique<Surface>();
        s->model = model;
        s->generation = gen;
        s->size = size;
        const ProgressCallback progress = [&job](std::string_view ph, double f) { return job.progress(ph, f); };
        if (adapt) {
          AdaptOutcome o = adapt_and_replay(model->mesh, *param, file, req, progress);
          s->param = o.param;
          s->canvas = std::move(o.canvas);
          r.phase_ms = std::move(o.phase_ms);
          r.phase_ms.emplace_back("total", ms_since(t0));
          auto maps = std::make_shared<AdaptMaps>();
          maps->importance = std::move(o.importance);
          maps->stretch = std::move(o.stretch);
          maps->ls2 = std::move(o.ls2);
          maps->coarse = std::move(o.coarse);
          maps->fine = std::move(o.fine);
          maps->accepted = o.accepted;
          maps->damping = o.damping;
          r.maps = std::move(maps);
          r.adapted = true;
        } else {
          s->param = param;
          s->canvas = std::make_unique<Canvas>(model->mesh, *param, size, size, file.background);
          for (size_t i = 0; i < file.strokes.size(); ++i) {
            if (!job.progress("replay", double(i) / file.strokes.size())) throw CancelledError();
            s->canvas->paint_stroke(file.strokes[i]);
          }
          r.phase_ms.emplace_back("replay", ms_since(t0));
        }
        s->painted = file.strokes.size();
        r.surface = std::move(s);
        return r;
      });
}

void App::maybe_start_rebuild() {
  if (!model_ || !surface_ || load_job_) return;
  const bool stale = surface_->generation != history_.generation() || surface_->size != adapt_.texture_size;
  if (rebuild_job_) {
    // A rebuild for an older history generation (undo / redo meanwhile) is abandoned, not awaited.
    if (rebuild_generation_ != history_.generation()) start_rebuild(false);
    return;
  }
  const bool want_adapt = adapt_pending_ && adapt_.mode != AdaptMode::None;
  if (stale || (want_adapt && !stroke_open_)) {
    start_rebuild(want_adapt && !stroke_open_);
    return;
  }
  // Pure appends (redo, decals): paint the missing strokes onto the current canvas.
  if (!stroke_open_) {
    const auto& strokes = history_.strokes();
    while (surface_->painted < strokes.size()) {
      surface_->canvas->paint_stroke(strokes[surface_->painted++]);
      texture_full_upload_ = true;
    }
  }
}

void App::swap_surface(std::unique_ptr<Surface> s) {
  const bool new_param = !surface_ || surface_->param != s->param;
  surface_ = std::move(s);
  ++surface_serial_;
  texture_full_upload_ = true;
  if (new_param) mesh_upload_ = true;
}

void App::poll_jobs() {
  retired_jobs_.erase(std::remove_if(retired_jobs_.begin(), retired_jobs_.end(),
                                     [](const auto& j) { return j->ready(); }),
                      retired_jobs_.end());
  if (compare_job_ && compare_job_->ready()) {
    try {
      comparison_ = std::make_shared<Comparison>(compare_job_->take());
    } catch (const std::exception& e) {
      add_message(std::string("comparison failed: ") + e.what(), true);
    }
    compare_job_.reset();
  }
  if (load_job_ && load_job_->ready()) {
    auto job = std::move(load_job_);
    try {
      LoadResult r = job->take();
      if (stroke_open_) end_paint();
      model_ = r.model;
      auto s = std::move(r.surface);
      history_.reset(std::move(pending_strokes_), pending_background_.value_or(history_.background()));
      pending_strokes_.clear();
      pending_background_.reset();
      if (history_.strokes().empty()) s->generation = history_.generation();
      swap_surface(std::move(s));
      camera_.frame(model_->box);
      add_recent(model_->path);
      char buf[64];
      std::snprintf(buf, sizeof buf, " in %.2f s", r.seconds);
      add_message("loaded " + model_->path + buf, false);
    } catch (const CancelledError&) {
      add_message("loading cancelled", false);
      pending_strokes_.clear();
    } catch (const std::exception& e) {
      add_message(e.what(), true);
      pending_strokes_.clear();
    }
  }
  if (rebuild_job_ && rebuild_job_->ready()) {
    auto job = std::move(rebuild_job_);
    try {
      RebuildResult r = job->take();
      if (r.surface->generation == history_.generation() && r.surface->model == model_ &&
          r.surface->size == adapt_.texture_size) {
        Surface& s = *r.surface;
        // Strokes finished while the job ran, then the open stroke: replayed before the swap.
        const auto& strokes = history_.strokes();
        while (s.painted < strokes.size()) s.canvas->paint_stroke(strokes[s.painted++]);
        if (stroke_open_) {
          surface_->canvas->end_stroke();
          s.canvas->begin_stroke(current_);
          for (const Vec3& d : current_.dabs) s.canvas->add_dab(d);
        }
        if (r.adapted) {
          last_cycle_ = r.phase_ms;
          maps_ = r.maps;
        }
        swap_surface(std::move(r.surface));
      }
    } catch (const CancelledError&) {
    } catch (const std::exception& e) {
      add_message(e.what(), true);
      adapt_pending_ = false;
    }
  }
  maybe_start_rebuild();
}

// ---- autosave ---------------------------------------------------------------------------------

void App::autosave_tick() {
  if (options_.recovery_dir.empty() || !model_) return;
  if (autosave_job_ && !autosave_job_->ready()) return;
  if (autosave_job_) {
    try {
      autosave_job_->take();
    } catch (const std::exception& e) {
      add_message(std::string("autosave failed: ") + e.what(), true);
    }
    autosave_job_.reset();
  }
  if (history_.version() == saved_version_ || stroke_open_) return;
  const auto now = Clock::now();
  if (!change_time_) change_time_ = now;
  const bool due = *change_time_ == Clock::time_point{} ||
                   std::chrono::duration<double>(now - *change_time_).count() >= options_.autosave_delay;
  if (!due) return;
  Project p;
  p.mesh_path = model_->path;
  p.strokes = history_.to_file();
  p.brush = brush_;
  p.view = view_;
  p.adapt = adapt_;
  p.camera = camera_;
  saved_version_ = history_.version();
  change_time_.reset();
  const auto path = recovery_path();
  autosave_job_ = std::make_unique<Job<int>>([p = std::move(p), path](Job<int>&) {
    write_project(path, p);
    return 0;
  });
}

// ---- frame ------------------------------------------------------------------------------------

void App::begin_frame() {
  poll_jobs();
  autosave_tick();
}

void App::render() {
  if (mesh_upload_ && surface_) {
    renderer_->set_mesh(model_->mesh, *surface_->param);
    mesh_upload_ = false;
  }
  if (surface_ && texture_full_upload_) {
    renderer_->set_texture(surface_->canvas->texture());
    texture_full_upload_ = false;
    dirty_ = {0, 0, -1, -1};
  } else if (surface_ && dirty_[2] >= dirty_[0]) {
    renderer_->update_texture(surface_->canvas->texture(), dirty_);
    dirty_ = {0, 0, -1, -1};
  }
  FrameView v;
  v.camera = camera_;
  v.has_mesh = surface_ != nullptr;
  v.wireframe = view_.wireframe;
  v.background = view_.background;
  if (cursor_hit_ && brush_.tool != Tool::Eyedropper && model_) {
    v.cursors.push_back({cursor_hit_->point, cursor_hit_->normal, world_radius()});
    if (brush_.symmetry_axis >= 0) {
      const int a = brush_.symmetry_axis;
      const double c = 0.5 * (model_->box.min[a] + model_->box.max[a]);
      Ray m = camera_.pixel_ray(mouse_x_, mouse_y_);
      m.origin[a] = 2 * c - m.origin[a];
      m.dir[a] = -m.dir[a];
      if (auto mh = model_->caster->intersect(m); mh && mh->front_facing)
        v.cursors.push_back({mh->point, mh->normal, world_radius()});
    }
  }
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

// ---- files ------------------------------------------------------------------------------------

void App::screenshot(const std::filesystem::path& path) { pending_screenshot_ = path; }

void App::save_history(const std::filesystem::path& path) {
  try {
    save_strokes(path, history_.to_file());
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::save_texture(const std::filesystem::path& path) {
  if (!surface_) return add_message("no texture to save", true);
  try {
    save_png(path, surface_->canvas->texture());
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::export_obj(const std::filesystem::path& dir) {
  if (!surface_) return add_message("nothing to export", true);
  try {
    const std::string name = std::filesystem::path(model_->path).stem().string();
    studio::export_obj(dir, name.empty() ? "model" : name, model_->mesh, *surface_->param,
                       surface_->canvas->texture());
    add_message("exported OBJ+MTL+PNG to " + dir.string(), false);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::export_glb(const std::filesystem::path& path) {
  if (!surface_) return add_message("nothing to export", true);
  try {
    studio::export_glb(path, model_->mesh, *surface_->param, surface_->canvas->texture());
    add_message("exported " + path.string(), false);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

void App::request_adapt() {
  if (adapt_.mode == AdaptMode::None) return add_message("choose an adaptation mode first", true);
  adapt_pending_ = true;
}

}  // namespace adaptex::studio

namespace adaptex::studio {
bool App::load_running() const { return load_job_ != nullptr; }
bool App::compare_running() const { return compare_job_ != nullptr; }

void App::request_compare() {
  if (!surface_ || compare_job_) return;
  auto model = model_;
  auto adaptive = surface_->param;
  auto tex = std::make_shared<ImageRGBA8>(surface_->canvas->texture());
  StrokeFile file = history_.to_file();
  const int size = surface_->size;
  compare_job_ = std::make_unique<Job<Comparison>>([model, adaptive, tex, file, size](Job<Comparison>&) {
    Comparison c;
    c.fixed_param = model->initial;
    c.adaptive_param = adaptive;
    Canvas fixed(model->mesh, *model->initial, size, size, file.background);
    for (const Stroke& s : file.strokes) fixed.paint_stroke(s);
    c.fixed_texture = fixed.texture();
    c.adaptive_texture = *tex;
    c.psnr_fixed = texture_psnr(model->mesh, *model->initial, c.fixed_texture, file);
    c.psnr_adaptive = texture_psnr(model->mesh, *adaptive, c.adaptive_texture, file);
    c.strokes = file.strokes.size();
    return c;
  });
}
}  // namespace adaptex::studio
