// camdyn (private) — the camshaft as a body (issue 40; include/camdyn/scene.hpp CamshaftSpec):
// what a mechanism with a [camshaft] adds to the network's.
//
//   Stations are unknowns whose coordinate is the shaft angle φ_i: polar inertia J_i in M,
//   segment stiffness GJ/L in K, Rayleigh damping αJ + βK_shaft in C (assembled by the network
//   assembly, src/mechanism/mechanism.cpp). The drive couples station d to the crank:
//     τ_d = k_d (θ_c(t) − φ_d) + c_d (θ̇_c(t) − φ̇_d),   θ_c(t) = θ(t) + Σ a_k sin(n_k θ(t) + p_k)
//   with −k_d φ_d − c_d φ̇_d in K and C and the crank's part k_d θ_c + c_d θ̇_c a force in r(t).
//   A cam contact j on cam i (station s, offset α_i) has the gap
//     g_j = T_j q + g₀_j − X_L(φ_s − α_i),        X_L = X_C − X_base (the lift above the base circle)
//   so its row over the unknowns is T̃_j = T_j − X_L′ e_sᵀ: the contact force F_j acts on the
//   follower through T_j and on the shaft as the torque −X_L′ F_j (virtual work), and
//     ġ_j = T̃_j q̇,    g̈_j = T̃_j q̈ − X_L″ φ̇_s².
//   The energy ledger treats the coupling as the driver: its power τ_d φ̇_d is the run's input
//   work, and the coupling's own spring and damper are not in the mechanism's stored energy or
//   dissipation.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"

namespace camdyn {

/// A cam's lift above its base circle at a shaft state and its derivatives in the shaft angle.
struct ShaftCamLift {
  double X = 0.0;    ///< X_L(φ_s − α)
  double dX = 0.0;   ///< ∂X_L/∂φ_s
  double ddX = 0.0;  ///< ∂²X_L/∂φ_s²
};

/// The camshaft of a mechanism: its stations' unknowns, its cams, the contacts on them and its
/// drive.
class CamShaft {
 public:
  /// @param scene a validated scene with a [camshaft].
  /// @param station_dof the mechanism's unknown of each station (inertias.size() entries).
  /// @param contact_cams for every contact of the mechanism, its cam (−1: not on the shaft).
  CamShaft(const Scene& scene, std::vector<int> station_dof, std::vector<int> contact_cams);

  int stations() const { return int(station_dof_.size()); }
  int cams() const { return int(cam_station_.size()); }
  /// The unknown of station i.
  int station_dof(int i) const { return station_dof_[std::size_t(i)]; }
  /// The drive station's unknown.
  int drive_dof() const { return station_dof_[std::size_t(drive_station_)]; }
  int drive_station() const { return drive_station_; }
  double drive_stiffness() const { return kd_; }
  double drive_damping() const { return cd_; }
  /// The crank's angle θ_c(t) [rad] and speed θ̇_c(t).
  void crank(double t, double* theta, double* omega) const;
  /// The coupling's torque τ_d on the drive station at (t, φ_d, φ̇_d).
  double drive_torque(double t, double phi, double phid) const;
  /// The crank's part of the drive's force in r(t): k_d θ_c + c_d θ̇_c.
  double drive_forcing(double t) const;

  /// Contact j's cam (−1: not on the shaft), its station's unknown and its cam's offset [rad].
  int contact_cam(int j) const { return std::size_t(j) < contact_cam_.size() ? contact_cam_[std::size_t(j)] : -1; }
  int contact_dof(int j) const { return station_dof(cam_station_[std::size_t(contact_cam(j))]); }
  /// Cam i's station and offset α_i [rad].
  int cam_station(int i) const { return cam_station_[std::size_t(i)]; }
  double cam_offset(int i) const { return cam_offset_[std::size_t(i)]; }
  /// The lift of contact j's cam at the unknowns q (contact_cam(j) ≥ 0).
  ShaftCamLift lift(int j, const double* q) const;
  /// The cam angle of cam i at q: φ_station − α_i [rad].
  double cam_angle(int i, const double* q) const { return q[station_dof(cam_station(i))] - cam_offset(i); }
  /// Add the contacts' torques on the shaft, −X_L′ F_j on contact j's station, to r.
  void add_contact_torques(const double* q, const double* F, int m, double* r) const;
  /// The stations' angles and speeds at t = 0: the crank's (an untwisted shaft).
  void initial_state(double* phi0, double* omega0) const;
  /// M⁻¹e_s for every station s (n × stations), set once by the mechanism.
  const Eigen::MatrixXd& station_response() const { return Z_; }
  void set_station_response(Eigen::MatrixXd Z) { Z_ = std::move(Z); }

 private:
  std::vector<int> station_dof_, cam_station_, contact_cam_;
  std::vector<double> cam_offset_;
  int drive_station_ = 0;
  double kd_ = 0.0, cd_ = 0.0, x_base_ = 0.0;
  std::vector<double> order_, amp_, phase_;  // the crank's orders, amplitudes [rad], phases [rad]
  CamDrive drive_;
  // one Cam per cam: its evaluation tracks the contact point from the previous call
  std::vector<std::unique_ptr<Cam>> cam_;
  Eigen::MatrixXd Z_;
};

/// The scene's network with the camshaft's stations, segments and bearing dampers added
/// (mechanism_camshaft.cpp). @pre scene.camshaft.present().
NetworkSpec network_with_camshaft(const Scene& scene);

}  // namespace camdyn
