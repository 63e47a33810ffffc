// camdyn — the registry of the single-follower stack's contact methods (solver.stack =
// "follower"): Lee's classic step, kept for comparison (bench: the located step's gain).
// Every other method runs on the mechanism (src/contact/contact_run.cpp,
// make_contact_method). Adding a method here: a RunContext subclass and one line in kMethods.
#include <stdexcept>

#include "legacy/run_context.hpp"

namespace camdyn {
namespace detail {

std::unique_ptr<RunContext> make_lee_classic(const Scene&, std::shared_ptr<const FollowerModel>,
                                             Observer*, const std::atomic<bool>*);

namespace {
bool lee_classic(const Scene& s) {
  return s.contact.model == ContactModel::Lee && s.contact.lee_step == LeeStepKind::Classic;
}

std::vector<ContactMethodEntry>& registry() {
  static std::vector<ContactMethodEntry> kMethods{
      {"lee (classic step)", &lee_classic, &make_lee_classic},
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
