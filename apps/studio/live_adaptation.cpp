/// \file live_adaptation.cpp
/// The studio's each-stroke session on a worker thread (see live_adaptation.h).
#include "live_adaptation.h"

#include <pthread.h>

#include <chrono>

#include "adaptex/core/errors.h"
#include "backend.h"
#include "settings.h"

namespace adaptex::studio {

LiveAdaptation::LiveAdaptation(std::shared_ptr<const Model> model, std::uint64_t generation,
                               const PaintSessionOptions& options, StrokeFile history)
    : model_(model.get()),
      generation_(generation),
      options_key_(session_options_key(options)),
      size_(options.texture_size) {
  queue_ = std::move(history.strokes);
  fed_ = queue_.size();
  settled_ = queue_.empty();  // nothing to adapt to
  thread_ = std::thread([this, model = std::move(model), options, bg = history.background]() mutable {
    pthread_setname_np(pthread_self(), "adaptex-adapt");  // named in top, gdb and the GUI tests
    run(std::move(model), options, bg);
  });
}

LiveAdaptation::~LiveAdaptation() { stop_and_join(); }

bool LiveAdaptation::serves(const Model* model, std::uint64_t generation, const std::string& options_key) const {
  return model == model_ && generation == generation_ && options_key == options_key_ && !done_;
}

void LiveAdaptation::feed(std::vector<Stroke> strokes) {
  if (strokes.empty()) return;
  const size_t n = strokes.size();
  push(std::move(strokes), [&] { fed_ += n; });
}

size_t LiveAdaptation::fed() const {
  std::lock_guard lock(mutex_);
  return fed_;
}

bool LiveAdaptation::settled() const {
  std::lock_guard lock(mutex_);
  return settled_ && adapted_ == fed_;
}

bool LiveAdaptation::caught_up() const {
  std::lock_guard lock(mutex_);
  return ((settled_ && adapted_ == fed_) || done_) && !update_ && !error_;
}

void LiveAdaptation::publish(const std::shared_ptr<const Model>& model, LiveSession& session) {
  std::optional<RebuildResult> u;
  if (session.changed()) {
    const auto t0 = std::chrono::steady_clock::now();
    std::shared_ptr<const RayCaster> caster;  // built while the canvas is
    SessionOutcome o = session.snapshot([&](const TriMesh& m) {
      if (&m != model->mesh.get()) caster = std::make_shared<const RayCaster>(m);
    });
    u = surface_from_session(model, std::move(o), std::move(caster));
    // The copy for the UI: its canvas (texel map), picking on a refined mesh, shading normals.
    u->phase_ms.emplace_back(
        "snapshot", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    u->surface->generation = generation_;
    u->surface->size = size_;
    u->surface->painted = session.strokes();
  }
  // One step for the UI: the surface, the strokes it adapted and whether it is settled.
  std::lock_guard lock(mutex_);
  if (u) update_ = std::move(u);  // an older one not yet taken is dropped
  ++cycles_;
  adapted_ = session.strokes();
  settled_ = session.settled();
}

void LiveAdaptation::run(std::shared_ptr<const Model> model, PaintSessionOptions options, Vec3 background) {
  run_guarded([&] {
    LiveSession session(model->mesh, *model->initial, options, background,
                        [this](std::string_view phase, double f) { return keep_going(phase, f); });
    while (std::optional<std::vector<Stroke>> batch = next_batch(session.settled())) {
      try {
        if (batch->empty())
          session.settle();
        else
          session.add(*batch);
      } catch (const CancelledError&) {
        if (stop_) break;
        continue;  // a settle gave way to new strokes
      }
      publish(model, session);
    }
  });
}

}  // namespace adaptex::studio
