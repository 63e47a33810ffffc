// camdyn (private) — the contact rows of IdaHeldSet's DAE (ida_engine.cpp): a row T_j with its
// cam, and on a [camshaft] the cam's lift at its station's angle (mechanism/camshaft.hpp):
// contact j on cam i of station s has the gap g_j = T_j q + g₀ − X_L(φ_s − α_i), so its row
// over the unknowns is T̃_j = T_j − X_L′ e_sᵀ and ġ_j = T_j v − X_L′ φ̇_s (a free station), or
// X_L(θ_c(t) − α_i) and ġ_j = T_j v − X_L′ θ̇_c (the prescribed drive station: no unknown).
#pragma once

#include <utility>
#include <vector>

#include "camdyn/cam.hpp"
#include "mechanism/camshaft.hpp"
#include "mechanism/mechanism.hpp"

namespace camdyn {
namespace ida_rows {

/// A contact row: its nonzeros (T_j is sparse: one entry for a single follower).
struct Row {
  std::vector<std::pair<long, double>> nz;
  double g0 = 0.0;
  bool cam = false;
  int contact = -1;    ///< the mechanism's contact index
  bool shaft = false;  ///< on a camshaft's cam
  int sdof = -1;       ///< on a cam of a free station: the station's unknown (the row's −X_L′ column)
  double dot(const double* x) const {
    double s = 0.0;
    for (const auto& e : nz) s += e.second * x[e.first];
    return s;
  }
};

inline Row row_of(const Mechanism& mech, int j) {
  const MechanismContact& c = mech.contacts()[std::size_t(j)];
  Row r;
  for (long i = 0; i < c.t.size(); ++i)
    if (c.t[i] != 0.0) r.nz.emplace_back(i, c.t[i]);
  r.g0 = c.g0;
  r.cam = c.cam;
  r.contact = j;
  if (const CamShaft* cs = mech.camshaft(); cs && cs->contact_cam(j) >= 0) {
    r.shaft = true;
    r.sdof = cs->contact_dof(j);
  }
  return r;
}

/// The cam's motion along a row at (t, q, v): the lift X and Ẋ its gap and gap rate subtract;
/// on a free station also X_L′ and X_L″ in its station's angle (0 otherwise).
struct RowCam {
  double X = 0.0, Xdot = 0.0, dX = 0.0, ddX = 0.0;
};

/// `drive`: the [cam]'s lift at t (the rows without a camshaft).
inline RowCam row_cam(const Row& h, const CamShaft* cs, const CamMotion& drive, double t, const double* q,
                      const double* v) {
  RowCam r;
  if (!h.cam) return r;
  if (!h.shaft) {
    r.X = drive.X;
    r.Xdot = drive.Xdot;
    return r;
  }
  if (h.sdof >= 0) {
    const ShaftCamLift L = cs->lift(h.contact, q);
    r.X = L.X;
    r.Xdot = L.dX * v[h.sdof];
    r.dX = L.dX;
    r.ddX = L.ddX;
    return r;
  }
  const CamMotion m = cs->contact_cam_motion(h.contact, t, q, v);
  r.X = m.X;
  r.Xdot = m.Xdot;
  return r;
}

}  // namespace ida_rows
}  // namespace camdyn
