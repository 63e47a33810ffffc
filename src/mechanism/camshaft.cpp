// camdyn — the camshaft as a body (src/mechanism/camshaft.hpp has the model).
#include "mechanism/camshaft.hpp"

#include <cmath>

#include "cam/lift_base.hpp"

namespace camdyn {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}

CamShaft::CamShaft(const Scene& scene, std::vector<int> station_dof, std::vector<int> contact_cams)
    : station_dof_(std::move(station_dof)), contact_cam_(std::move(contact_cams)), drive_(scene.cam) {
  const CamshaftSpec& c = scene.camshaft;
  for (double s : c.cam_stations) cam_station_.push_back(int(s));
  cam_offset_.assign(cam_station_.size(), 0.0);
  for (std::size_t i = 0; i < c.cam_offsets_deg.size(); ++i) cam_offset_[i] = c.cam_offsets_deg[i] * kDeg;
  for (std::size_t i = 0; i < c.cam_offsets_crank_deg.size(); ++i)
    cam_offset_[i] = 0.5 * c.cam_offsets_crank_deg[i] * kDeg;
  drive_station_ = int(c.drive_station);
  prescribed_ = c.drive == CamshaftDrive::Prescribed;
  if (!prescribed_) {
    couplings_.push_back({station_dof_[std::size_t(drive_station_)], c.drive_stiffness, c.drive_damping});
  } else {  // the segments next to the prescribed station
    drive_inertia_ = c.inertias[std::size_t(drive_station_)];
    alpha_ = c.rayleigh_alpha;
    const int d = drive_station_;
    if (d > 0)
      couplings_.push_back({station_dof_[std::size_t(d - 1)], c.stiffnesses[std::size_t(d - 1)],
                            c.rayleigh_beta * c.stiffnesses[std::size_t(d - 1)]});
    if (std::size_t(d) + 1 < c.inertias.size())
      couplings_.push_back({station_dof_[std::size_t(d + 1)], c.stiffnesses[std::size_t(d)],
                            c.rayleigh_beta * c.stiffnesses[std::size_t(d)]});
  }
  order_ = c.crank_orders;
  for (double a : c.crank_amplitudes_deg) amp_.push_back(a * kDeg);
  for (double p : c.crank_phases_deg) phase_.push_back(p * kDeg);
  for (std::size_t i = 0; i < cam_station_.size(); ++i) cam_.push_back(std::make_unique<Cam>(scene.cam));
  x_base_ = cam_lift_base(*cam_.front(), scene.cam);
}

// θ_c = θ + Σ a sin(nθ + p): θ̇_c = ω(1 + Σ a n cos), θ̈_c = ω̇(1 + Σ a n cos) − ω² Σ a n² sin.
void CamShaft::crank(double t, double* theta, double* omega, double* acc) const {
  const double th = drive_.theta(t), w = drive_.omega(t);
  double a = th, ad = w, c = 1.0, s2 = 0.0;
  for (std::size_t k = 0; k < order_.size(); ++k) {
    const double arg = order_[k] * th + phase_[k];
    a += amp_[k] * std::sin(arg);
    ad += amp_[k] * order_[k] * w * std::cos(arg);
    c += amp_[k] * order_[k] * std::cos(arg);
    s2 += amp_[k] * order_[k] * order_[k] * std::sin(arg);
  }
  *theta = a;
  *omega = ad;
  if (acc) *acc = drive_.omega_dot(t) * c - w * w * s2;
}

void CamShaft::add_crank_forcing(double t, double* r) const {
  double th, w;
  crank(t, &th, &w);
  for (const Coupling& k : couplings_) r[k.dof] += k.k * th + k.c * w;
}

double CamShaft::coupling_power(double t, const double* q, const double* v) const {
  double th, w, p = 0.0;
  crank(t, &th, &w);
  for (const Coupling& k : couplings_) p += (k.k * (th - q[k.dof]) + k.c * (w - v[k.dof])) * v[k.dof];
  return p;
}

double CamShaft::coupling_energy(const double* q) const {
  double V = 0.0;
  for (const Coupling& k : couplings_) V += 0.5 * k.k * q[k.dof] * q[k.dof];
  return V;
}

double CamShaft::coupling_dissipation(const double* v) const {
  double P = 0.0;
  for (const Coupling& k : couplings_) P += k.c * v[k.dof] * v[k.dof];
  return P;
}

double CamShaft::drive_torque(double t, const double* q, const double* v, const double* F, int m) const {
  double th, w, acc;
  crank(t, &th, &w, &acc);
  double tau = 0.0;
  for (const Coupling& k : couplings_) tau += k.k * (th - q[k.dof]) + k.c * (w - v[k.dof]);
  if (!prescribed_) return tau;
  tau += drive_inertia_ * (acc + alpha_ * w);
  for (int j = 0; j < m; ++j)  // the reaction of the contact torque −X_L′F on the station
    if (on_prescribed_station(j) && F[j] != 0.0) tau += lift(j, t, q).dX * F[j];
  return tau;
}

double CamShaft::station_angle(int i, double t, const double* q) const {
  const int dof = station_dof(i);
  if (dof >= 0) return q[dof];
  double th, w;
  crank(t, &th, &w);
  return th;
}

double CamShaft::station_speed(int i, double t, const double* v) const {
  const int dof = station_dof(i);
  if (dof >= 0) return v[dof];
  double th, w;
  crank(t, &th, &w);
  return w;
}

ShaftCamLift CamShaft::lift(int j, const double* q) const {
  const int i = contact_cam(j);
  const CamMotion m = cam_[std::size_t(i)]->motion(q[station_dof(cam_station(i))] - cam_offset(i), 1.0, 0.0);
  return {m.X - x_base_, m.Xdot, m.Xddot};
}

ShaftCamLift CamShaft::lift(int j, double t, const double* q) const {
  const int i = contact_cam(j);
  const CamMotion m = cam_[std::size_t(i)]->motion(cam_angle(i, t, q), 1.0, 0.0);
  return {m.X - x_base_, m.Xdot, m.Xddot};
}

CamMotion CamShaft::contact_cam_motion(int j, double t, const double* q, const double* v) const {
  const int s = cam_station(contact_cam(j));
  const ShaftCamLift L = lift(j, t, q);
  CamMotion m;
  m.t = t;
  m.X = L.X;
  if (station_dof(s) >= 0) {
    const double w = v[station_dof(s)];
    m.Xdot = L.dX * w;
    m.Xddot = L.ddX * w * w;
    return m;
  }
  double th, w, acc;
  crank(t, &th, &w, &acc);
  m.Xdot = L.dX * w;
  m.Xddot = L.ddX * w * w + L.dX * acc;
  return m;
}

void CamShaft::add_contact_torques(const double* q, const double* F, int m, double* r) const {
  for (int j = 0; j < m; ++j)
    if (on_free_station(j) && F[j] != 0.0) r[contact_dof(j)] -= lift(j, q).dX * F[j];
}

void CamShaft::initial_state(double* phi0, double* omega0) const { crank(0.0, phi0, omega0); }

}  // namespace camdyn
