// camdyn (private) — cvode-bdf's order limits on a mechanism for the scene's method: the
// one rule the methods on cvode-bdf give CVODE (OdeSystem::max_order,
// stability_limit_detection) and the summary's tolerance words state
// (src/run/summary_builder.cpp: describe_tolerance).
#pragma once

#include "camdyn/scene.hpp"
#include "engine/ode_engine.hpp"
#include "mechanism/mechanism.hpp"

namespace camdyn {
namespace detail {

/// CVODE's BDF order limits for one run.
struct BdfOrderLimit {
  int max_order = 5;                       ///< the largest BDF order (CVodeSetMaxOrd), 1 … 5
  bool stability_limit_detection = false;  ///< CVodeSetStabLimDet
};

/// The BDF order limits of the method `scene` runs on cvode-bdf (`make_contact_method`:
/// Lee's and the holonomic model run Lee in CVODE, `event` and `penalty` their own method)
/// on `mech`:
/// - an elastic body whose internal modes are stiff (MechanismTraits::stiff_internal_modes,
///   the elastic_bar follower), any method: BDF ≤ 2 at rtol > 1e-8 (its undamped fast modes
///   sit on the imaginary axis, where orders 3–5 are not A-stable); at rtol ≤ 1e-8 its steps
///   resolve those modes and higher orders pay: ≤ 5 with CVODE's stability-limit detection
///   (docs/background/method_notes.md, "BDF orders on a single elastic follower");
/// - otherwise Lee in CVODE: ≤ 4 (a small re-impact after a short flight on a valve train
///   is met more closely than at 5, for fewer steps than at 3: method_notes.md, "BDF order
///   of Lee in CVODE");
/// - otherwise the event and penalty methods: ≤ 5, CVODE's default.
inline BdfOrderLimit cvode_bdf_order(const Scene& scene, const MechanicalSystem& mech) {
  BdfOrderLimit o;
  if (mech.traits().stiff_internal_modes) {
    const bool tight = scene.solver.rtol <= 1e-8;
    o.max_order = tight ? 5 : 2;
    o.stability_limit_detection = tight;
    return o;
  }
  const bool lee = scene.contact.model == ContactModel::Lee || scene.contact.model == ContactModel::Holonomic;
  o.max_order = lee ? 4 : 5;
  return o;
}

/// `sys`'s cvode-bdf order limits (OdeSystem::max_order, stability_limit_detection) from
/// cvode_bdf_order: every method on cvode-bdf sets them through this (event, Lee in CVODE,
/// penalty).
inline void set_cvode_bdf_order(const Scene& scene, const MechanicalSystem& mech, OdeSystem& sys) {
  const BdfOrderLimit o = cvode_bdf_order(scene, mech);
  sys.max_order = o.max_order;
  sys.stability_limit_detection = o.stability_limit_detection;
}

}  // namespace detail
}  // namespace camdyn
