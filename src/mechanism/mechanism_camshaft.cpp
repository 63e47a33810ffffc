// camdyn — the mechanism builder's camshaft part (camshaft.hpp has the model): the network
// with the shaft's stations, segments and bearing dampers, and the CamShaft attached to the
// built mechanism (its stations' unknowns, each cam contact's cam, the stations' mass
// responses, the model description with the shaft's torsional frequencies).
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "cam/format.hpp"  // detail::fmt
#include "mechanism/camshaft.hpp"
#include "mechanism/mechanism.hpp"

namespace camdyn {

using detail::fmt;

/// The scene's network with the camshaft's stations, segments and bearing dampers added
/// (stations start at the crank's angle and speed: an untwisted shaft). A prescribed drive
/// station is no node: its segments run from their other station to ground (their crank
/// forcing is the CamShaft's couplings').
NetworkSpec network_with_camshaft(const Scene& scene) {
  const CamshaftSpec& c = scene.camshaft;
  NetworkSpec net = scene.network;
  double phi0 = 0.0, w0 = 0.0;
  CamShaft(scene, std::vector<int>(c.inertias.size(), 0), {}).initial_state(&phi0, &w0);
  const long fixed = c.drive == CamshaftDrive::Prescribed ? c.drive_station : -1;
  auto node = [&](std::size_t i) { return long(i) == fixed ? std::string("ground") : "shaft_" + std::to_string(i); };
  for (std::size_t i = 0; i < c.inertias.size(); ++i) {
    if (long(i) == fixed) continue;
    NodeSpec nd;
    nd.name = "shaft_" + std::to_string(i);
    nd.mass = c.inertias[i];
    nd.initial_displacement = phi0;
    nd.initial_velocity = w0;
    net.nodes.push_back(nd);
    if (c.rayleigh_alpha > 0.0) {
      ElementSpec d;
      d.name = "shaft_bearing_" + std::to_string(i);
      d.kind = ElementKind::Dashpot;
      d.nodes = {nd.name, "ground"};
      d.damping = c.rayleigh_alpha * c.inertias[i];
      net.elements.push_back(d);
    }
  }
  for (std::size_t i = 0; i < c.stiffnesses.size(); ++i) {
    ElementSpec e;
    e.name = "shaft_segment_" + std::to_string(i);
    e.kind = ElementKind::Spring;
    e.nodes = {node(i), node(i + 1)};
    e.stiffness = c.stiffnesses[i];
    e.damping = c.rayleigh_beta * c.stiffnesses[i];
    net.elements.push_back(e);
  }
  return net;
}

std::vector<double> held_frequencies_hz(const Mechanism& mech, const double* q, const std::vector<int>& held,
                                        const double* F) {
  const CamShaft* cs = mech.camshaft();
  const int n = mech.n(), k = int(held.size());
  Eigen::MatrixXd M = Eigen::MatrixXd(mech.M()), K = Eigen::MatrixXd(mech.K()), T(k, n);
  for (int i = 0; i < k; ++i) {
    const int j = held[std::size_t(i)];
    T.row(i) = mech.T().row(j);
    if (cs && cs->on_free_station(j)) {
      const ShaftCamLift L = cs->lift(j, q);
      const int s = cs->contact_dof(j);
      T(i, s) -= L.dX;
      K(s, s) += L.ddX * F[j];
    }
  }
  Eigen::MatrixXd N = Eigen::MatrixXd::Identity(n, n);  // an orthonormal basis of the held rows' null space
  if (k > 0) {
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(T.transpose());
    const Eigen::Index r = qr.rank();
    if (r >= n) return {};
    N = (qr.householderQ() * Eigen::MatrixXd::Identity(n, n)).rightCols(n - r);
  }
  Eigen::MatrixXd Kn = N.transpose() * K * N, Mn = N.transpose() * M * N;
  Kn = 0.5 * (Kn + Kn.transpose()).eval();
  Mn = 0.5 * (Mn + Mn.transpose()).eval();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kn, Mn, Eigen::EigenvaluesOnly);
  std::vector<double> f;
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i)
    f.push_back(std::sqrt(std::max(es.eigenvalues()[i], 0.0)) / (2 * 3.14159265358979323846));
  return f;
}

void Mechanism::attach_camshaft(const Scene& scene, const NetworkSpec& net, const std::vector<int>& red,
                                const std::map<std::string, int>& index) {
  const CamshaftSpec& c = scene.camshaft;
  std::vector<int> station_dof, contact_cam;
  for (std::size_t i = 0; i < c.inertias.size(); ++i) {
    const auto it = index.find("shaft_" + std::to_string(i));
    station_dof.push_back(it == index.end() ? -1 : red[it->second]);  // −1: the prescribed drive station
  }
  int k = 0;  // the cam contacts in order
  for (const ContactPointSpec& cs : net.contacts) {
    if (cs.kind != ContactPointKind::Cam) {
      contact_cam.push_back(-1);
      continue;
    }
    contact_cam.push_back(c.contact_cams.empty() ? k : int(c.contact_cams[std::size_t(k)]));
    ++k;
  }
  auto cs = std::make_shared<CamShaft>(scene, station_dof, contact_cam);
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(n_, Eigen::Index(station_dof.size()));
  for (std::size_t i = 0; i < station_dof.size(); ++i) {
    if (station_dof[i] < 0) continue;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n_);
    e[station_dof[i]] = 1.0;
    Z.col(Eigen::Index(i)) = Mldlt_.solve(e);
  }
  cs->set_station_response(std::move(Z));
  camshaft_ = cs;
  std::ostringstream d;
  d << "camshaft: " << c.inertias.size() << " stations, " << c.cam_stations.size() << " cams, drive at station "
    << c.drive_station;
  if (c.drive == CamshaftDrive::Prescribed)
    d << " (prescribed: the crank's angle)";
  else
    d << " (k " << fmt(c.drive_stiffness) << ", c " << fmt(c.drive_damping) << ")";
  for (std::size_t j = 0; j < contact_cam.size(); ++j)
    if (contact_cam[j] >= 0)
      d << "; '" << net.contacts[j].name << "' on cam " << contact_cam[j] << " (station "
        << camshaft_->cam_station(contact_cam[j]) << ", offset "
        << fmt(camshaft_->cam_offset(contact_cam[j]) * 180.0 / 3.14159265358979323846) << " deg)";
  std::vector<int> free;  // the stations that are unknowns
  for (int s : station_dof)
    if (s >= 0) free.push_back(s);
  if (!free.empty()) {  // the shaft's torsional frequencies with the crank held and the trains apart
    const Eigen::Index N = Eigen::Index(free.size());
    Eigen::MatrixXd Ms(N, N), Ks(N, N);  // the stations' block (the shaft couples to the trains only by contacts)
    for (Eigen::Index i = 0; i < N; ++i)
      for (Eigen::Index j = 0; j < N; ++j) {
        Ms(i, j) = M_.coeff(free[std::size_t(i)], free[std::size_t(j)]);
        Ks(i, j) = K_.coeff(free[std::size_t(i)], free[std::size_t(j)]);
      }
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ks, Ms, Eigen::EigenvaluesOnly);
    d << "; torsional frequencies (crank held, trains apart):";
    for (Eigen::Index i = 0; i < std::min<Eigen::Index>(N, 3); ++i)
      d << (i ? ", " : " ") << fmt(std::sqrt(std::max(es.eigenvalues()[i], 0.0)) / (2 * 3.14159265358979323846))
        << " Hz";
  }
  desc_.network.push_back(d.str());
}

}  // namespace camdyn
