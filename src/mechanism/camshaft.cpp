// camdyn — the camshaft as a body (src/mechanism/camshaft.hpp has the model).
#include "mechanism/camshaft.hpp"

#include <cmath>

#include "camdyn/initial_state.hpp"  // cam_lift_base

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
  kd_ = c.drive_stiffness;
  cd_ = c.drive_damping;
  order_ = c.crank_orders;
  for (double a : c.crank_amplitudes_deg) amp_.push_back(a * kDeg);
  for (double p : c.crank_phases_deg) phase_.push_back(p * kDeg);
  for (std::size_t i = 0; i < cam_station_.size(); ++i) cam_.push_back(std::make_unique<Cam>(scene.cam));
  x_base_ = cam_lift_base(*cam_.front(), scene.cam);
}

void CamShaft::crank(double t, double* theta, double* omega) const {
  const double th = drive_.theta(t), w = drive_.omega(t);
  double a = th, ad = w;
  for (std::size_t k = 0; k < order_.size(); ++k) {
    const double arg = order_[k] * th + phase_[k];
    a += amp_[k] * std::sin(arg);
    ad += amp_[k] * order_[k] * w * std::cos(arg);
  }
  *theta = a;
  *omega = ad;
}

double CamShaft::drive_torque(double t, double phi, double phid) const {
  double th, w;
  crank(t, &th, &w);
  return kd_ * (th - phi) + cd_ * (w - phid);
}

double CamShaft::drive_forcing(double t) const {
  double th, w;
  crank(t, &th, &w);
  return kd_ * th + cd_ * w;
}

ShaftCamLift CamShaft::lift(int j, const double* q) const {
  const int i = contact_cam(j);
  const CamMotion m = cam_[std::size_t(i)]->motion(cam_angle(i, q), 1.0, 0.0);
  return {m.X - x_base_, m.Xdot, m.Xddot};
}

void CamShaft::add_contact_torques(const double* q, const double* F, int m, double* r) const {
  for (int j = 0; j < m; ++j)
    if (contact_cam(j) >= 0 && F[j] != 0.0) r[contact_dof(j)] -= lift(j, q).dX * F[j];
}

void CamShaft::initial_state(double* phi0, double* omega0) const { crank(0.0, phi0, omega0); }

}  // namespace camdyn
