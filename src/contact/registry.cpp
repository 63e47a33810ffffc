// camdyn — the registry of contact methods: which scene runs which method.
// Adding a method: its file under src/contact/ (a RunContext subclass and a factory) and
// one line in kMethods below.
#include <stdexcept>

#include "run_context.hpp"

namespace camdyn {
namespace detail {

std::unique_ptr<RunContext> make_lee_located(const Scene&, std::shared_ptr<const FollowerModel>,
                                             Observer*, const std::atomic<bool>*);
std::unique_ptr<RunContext> make_lee_multistep(const Scene&, std::shared_ptr<const FollowerModel>,
                                               Observer*, const std::atomic<bool>*);
std::unique_ptr<RunContext> make_lee_classic(const Scene&, std::shared_ptr<const FollowerModel>,
                                             Observer*, const std::atomic<bool>*);
std::unique_ptr<RunContext> make_penalty(const Scene&, std::shared_ptr<const FollowerModel>,
                                         Observer*, const std::atomic<bool>*);
std::unique_ptr<RunContext> make_event_driven(const Scene&, std::shared_ptr<const FollowerModel>,
                                              Observer*, const std::atomic<bool>*);

namespace {
bool lee_located(const Scene& s) {
  return s.contact.model == ContactModel::Lee && s.contact.lee_step == LeeStepKind::Located;
}
// Lee's located step on cvode-bdf for an elastic follower: the three levels inside
// CVODE's step (lee_multistep.cpp). A rigid follower keeps the located step (its held
// state is exact and the step map affine: no restarts to save).
bool lee_multistep(const Scene& s) {
  return lee_located(s) && s.solver.integrator == Integrator::CvodeBdf && s.follower.kind != FollowerKind::Rigid;
}
bool lee_classic(const Scene& s) {
  return s.contact.model == ContactModel::Lee && s.contact.lee_step == LeeStepKind::Classic;
}
bool penalty(const Scene& s) { return s.contact.model == ContactModel::Penalty; }
bool event_or_holonomic(const Scene& s) {
  return s.contact.model == ContactModel::Event || s.contact.model == ContactModel::Holonomic;
}

std::vector<ContactMethodEntry>& registry() {
  static std::vector<ContactMethodEntry> kMethods{
      {"lee (located step, multistep engine)", &lee_multistep, &make_lee_multistep},
      {"lee (located step)", &lee_located, &make_lee_located},
      {"lee (classic step)", &lee_classic, &make_lee_classic},
      {"penalty", &penalty, &make_penalty},
      {"event-driven / holonomic", &event_or_holonomic, &make_event_driven},
  };
  return kMethods;
}
}  // namespace

const std::vector<ContactMethodEntry>& contact_methods() { return registry(); }

void register_contact_method(const ContactMethodEntry& entry) {
  registry().insert(registry().begin(), entry);
}

std::unique_ptr<RunContext> make_contact_method(const Scene& scene,
                                                std::shared_ptr<const FollowerModel> model,
                                                Observer* obs, const std::atomic<bool>* stop) {
  for (const ContactMethodEntry& e : registry())
    if (e.selects(scene)) return e.make(scene, std::move(model), obs, stop);
  throw std::logic_error(std::string("no contact method for contact.model = ") +
                         to_string(scene.contact.model));
}

}  // namespace detail
}  // namespace camdyn
