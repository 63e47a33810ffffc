// camdyn — the nonlinear element kinds of a scene (element.hpp: make_element).
#include <stdexcept>

#include "camdyn/network.hpp"
#include "mechanism/element.hpp"
#include "mechanism/elements/progressive_spring.hpp"
#include "mechanism/elements/guide_friction.hpp"
#include "mechanism/elements/gas_load.hpp"
#include "camdyn/scene.hpp"
#include "mechanism/elements/hydraulic_lash_adjuster.hpp"

namespace camdyn {

std::unique_ptr<Element> make_element(const ElementSpec& spec, const std::string& name, const Scene* scene) {
  switch (spec.kind) {
    case ElementKind::Spring:
    case ElementKind::Dashpot:
    case ElementKind::Bar:
    case ElementKind::Lever: return nullptr;  // linear: assembled into M, C, K, f₀
    case ElementKind::ProgressiveSpring: return std::make_unique<ProgressiveSpring>(spec, name);
    case ElementKind::GuideFriction: return std::make_unique<GuideFriction>(spec, name);
    case ElementKind::GasLoad:
      if (!scene) throw std::logic_error("make_element: a gas_load needs the scene's cam drive");
      return std::make_unique<GasLoad>(spec, name, scene->cam);
    case ElementKind::HydraulicLashAdjuster: return std::make_unique<HydraulicLashAdjuster>(spec, name);
  }
  throw std::logic_error("make_element: unknown element kind");
}

}  // namespace camdyn
