// camdyn — the mechanism builder's camshaft part (camshaft.hpp has the model): the network
// with the shaft's stations, segments and bearing dampers, and the CamShaft attached to the
// built mechanism (its stations' unknowns, each cam contact's cam, the stations' mass
// responses, the model description with the shaft's torsional frequencies).
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
/// (stations start at the crank's angle and speed: an untwisted shaft).
NetworkSpec network_with_camshaft(const Scene& scene) {
  const CamshaftSpec& c = scene.camshaft;
  NetworkSpec net = scene.network;
  double phi0 = 0.0, w0 = 0.0;
  CamShaft(scene, std::vector<int>(c.inertias.size(), 0), {}).initial_state(&phi0, &w0);
  for (std::size_t i = 0; i < c.inertias.size(); ++i) {
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
    e.nodes = {"shaft_" + std::to_string(i), "shaft_" + std::to_string(i + 1)};
    e.stiffness = c.stiffnesses[i];
    e.damping = c.rayleigh_beta * c.stiffnesses[i];
    net.elements.push_back(e);
  }
  return net;
}

void Mechanism::attach_camshaft(const Scene& scene, const NetworkSpec& net, const std::vector<int>& red,
                                const std::map<std::string, int>& index) {
  const CamshaftSpec& c = scene.camshaft;
  std::vector<int> station_dof, contact_cam;
  for (std::size_t i = 0; i < c.inertias.size(); ++i)
    station_dof.push_back(red[index.at("shaft_" + std::to_string(i))]);
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
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n_);
    e[station_dof[i]] = 1.0;
    Z.col(Eigen::Index(i)) = Mldlt_.solve(e);
  }
  cs->set_station_response(std::move(Z));
  camshaft_ = cs;
  std::ostringstream d;
  d << "camshaft: " << c.inertias.size() << " stations, " << c.cam_stations.size() << " cams, drive at station "
    << c.drive_station << " (k " << fmt(c.drive_stiffness) << ", c " << fmt(c.drive_damping) << ")";
  for (std::size_t j = 0; j < contact_cam.size(); ++j)
    if (contact_cam[j] >= 0)
      d << "; '" << net.contacts[j].name << "' on cam " << contact_cam[j] << " (station "
        << camshaft_->cam_station(contact_cam[j]) << ", offset "
        << fmt(camshaft_->cam_offset(contact_cam[j]) * 180.0 / 3.14159265358979323846) << " deg)";
  {  // the shaft's torsional frequencies with the crank held and the trains apart
    const Eigen::Index N = Eigen::Index(station_dof.size());
    Eigen::MatrixXd Ms(N, N), Ks(N, N);  // the stations' block (the shaft couples to the trains only by contacts)
    for (Eigen::Index i = 0; i < N; ++i)
      for (Eigen::Index j = 0; j < N; ++j) {
        Ms(i, j) = M_.coeff(station_dof[std::size_t(i)], station_dof[std::size_t(j)]);
        Ks(i, j) = K_.coeff(station_dof[std::size_t(i)], station_dof[std::size_t(j)]);
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
