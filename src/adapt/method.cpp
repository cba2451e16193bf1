// The registry of adaptation methods (method.h).
#include "adaptex/adapt/method.h"

#include <deque>
#include <mutex>

#include "adaptex/adapt/density_flow_method.h"
#include "adaptex/core/errors.h"
#include "thesis/thesis_methods.h"

namespace adaptex {

namespace {
/// The registered methods, the built-in ones first: one line each.
struct Registry {
  std::mutex mutex;
  std::deque<AdaptMethodInfo> methods{  // a deque: registering never moves an entry (AdaptMode keeps its name)
      {"none", "keep the layout", nullptr},
      {"single", "the thesis' relaxation on one grid (§3.7)", make_single_method},
      {"two-stage", "the thesis' coarse then fine relaxation (§3.8)", make_two_stage_method},
      {"density-flow", "error-model density reached by a flow that cannot fold (default)",
       [] { return std::make_unique<DensityFlowMethod>(); }}};
};

Registry& registry() {
  static Registry r;
  return r;
}

const AdaptMethodInfo* find(Registry& r, std::string_view name) {
  for (const AdaptMethodInfo& m : r.methods)
    if (m.name == name) return &m;
  return nullptr;
}
}  // namespace

void register_adapt_method(AdaptMethodInfo info) {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (info.name.empty() || !info.make) throw InvalidInputError("register_adapt_method: a method needs a name and a factory");
  if (find(r, info.name)) throw InvalidInputError("register_adapt_method: '" + info.name + "' is already registered");
  r.methods.push_back(std::move(info));
}

std::vector<const AdaptMethodInfo*> adapt_methods() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<const AdaptMethodInfo*> out;
  for (const AdaptMethodInfo& m : r.methods) out.push_back(&m);
  return out;
}

const AdaptMethodInfo* find_adapt_method(AdaptMode mode) {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  return find(r, mode.name());
}

std::unique_ptr<AdaptMethod> make_adapt_method(AdaptMode mode) {
  const AdaptMethodInfo* m = find_adapt_method(mode);
  if (!m) throw InvalidInputError(std::string("unknown adapt mode '") + mode.name() + "'");
  if (!m->make) throw InvalidInputError(std::string("adapt mode '") + mode.name() + "' has no warp method");
  return m->make();
}

const char* to_string(AdaptMode mode) { return mode.name(); }

std::vector<AdaptMode> adapt_modes() {
  std::vector<AdaptMode> modes;
  for (const AdaptMethodInfo* m : adapt_methods()) modes.emplace_back(m->name.c_str());
  return modes;
}

AdaptMode parse_adapt_mode(const std::string& name) {
  const std::vector<const AdaptMethodInfo*> methods = adapt_methods();
  std::string known;
  for (size_t k = 0; k < methods.size(); ++k) {
    if (name == methods[k]->name) return AdaptMode(methods[k]->name.c_str());
    known += (k == 0 ? "" : k + 1 == methods.size() ? " or " : ", ") + methods[k]->name;
  }
  if (name == "two_stage" || name == "twostage") return AdaptMode::TwoStage;
  if (name == "density_flow") return AdaptMode::DensityFlow;
  throw InvalidInputError("unknown adapt mode '" + name + "' (expected " + known + ")");
}

}  // namespace adaptex
