/// \file live_material.cpp
/// The studio's layered-material session on a worker thread (see live_material.h).
#include "live_material.h"

#include <pthread.h>

#include <chrono>

#include "adaptex/core/errors.h"
#include "backend.h"
#include "settings.h"

namespace adaptex::studio {

LiveMaterial::LiveMaterial(std::shared_ptr<const Model> model, std::uint64_t generation,
                           const PaintSessionOptions& options, MaterialStrokeFile file)
    : model_(model.get()), options_key_(session_options_key(options)), size_(options.texture_size) {
  fed_generation_ = done_generation_ = generation;
  settle_now_ = true;  // nothing will come soon: the document as it is, at once
  thread_ = std::thread([this, model = std::move(model), options, file = std::move(file)]() mutable {
    pthread_setname_np(pthread_self(), "adaptex-adapt");  // named in top, gdb and the GUI tests
    run(std::move(model), options, std::move(file));
  });
}

LiveMaterial::~LiveMaterial() { stop_and_join(); }

bool LiveMaterial::serves(const Model* model, const std::string& options_key) const {
  return model == model_ && options_key == options_key_ && !done_;
}

std::uint64_t LiveMaterial::generation() const {
  std::lock_guard lock(mutex_);
  return fed_generation_;
}

void LiveMaterial::feed(MaterialFeed stroke) {
  const std::uint64_t generation = stroke.generation;
  std::vector<MaterialFeed> one;
  one.push_back(std::move(stroke));
  push(std::move(one), [&] {
    fed_generation_ = generation;
    settled_ = false;
  });
}

bool LiveMaterial::caught_up() const {
  std::lock_guard lock(mutex_);
  return ((settled_ && done_generation_ == fed_generation_) || done_) && !update_ && !error_;
}

void LiveMaterial::add_batch(MaterialLiveSession& session, const std::vector<MaterialFeed>& batch) {
  for (size_t k = 0; k < batch.size();) {
    std::vector<MaterialStroke> run{batch[k].stroke};
    size_t e = k + 1;
    for (; e < batch.size() && batch[e].layer == batch[k].layer && batch[e].mask == batch[k].mask; ++e)
      run.push_back(batch[e].stroke);
    session.add(batch[k].layer, run, batch[k].mask);
    k = e;
  }
}

void LiveMaterial::run(std::shared_ptr<const Model> model, PaintSessionOptions options, MaterialStrokeFile file) {
  const auto progress = [this](std::string_view phase, double f) { return keep_going(phase, f); };
  run_guarded([&] {
    const MaterialValue background = file.background;
    std::shared_ptr<const RayCaster> caster;  // picking on the mesh last shown
    std::shared_ptr<const TriMesh> caster_mesh;
    auto show = [&](MaterialOutcome o, std::uint64_t generation, bool settled) {
      if (o.mesh != caster_mesh) {
        caster_mesh = o.mesh;
        caster = o.mesh == model->mesh ? model->caster : std::make_shared<const RayCaster>(*o.mesh);
      }
      RebuildResult r = surface_from_material(model, std::move(o), background, size_, options.padding, caster);
      r.surface->generation = generation;
      r.surface->settled = settled;
      std::lock_guard lock(mutex_);
      update_ = std::move(r);  // an older one not yet taken is dropped
      done_generation_ = generation;
      settled_ = settled && fed_generation_ == generation;
      ++cycles_;
    };
    std::uint64_t generation = 0;
    {
      std::lock_guard lock(mutex_);
      generation = fed_generation_;
    }
    MaterialLiveSession session(model->mesh, *model->initial, std::move(file), options, progress);
    show(session.snapshot(), generation, false);
    bool settled = false;  // the worker's own view: a batch unsettles, a settle settles
    while (std::optional<std::vector<MaterialFeed>> batch = next_batch(settled)) {
      try {
        if (batch->empty()) {
          MaterialOutcome o = paint_material_history(model->mesh, *model->initial, session.history(), options, progress);
          ++settles_;
          show(std::move(o), generation, true);
          settled = true;
        } else {
          generation = batch->back().generation;
          add_batch(session, *batch);
          show(session.snapshot(), generation, false);
          settled = false;
        }
      } catch (const CancelledError&) {
        if (stop_) break;  // else a settle gave way to new strokes
      }
    }
  });
}

}  // namespace adaptex::studio
