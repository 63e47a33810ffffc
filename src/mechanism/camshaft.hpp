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
//   A prescribed drive (camshaft.drive = "prescribed"): station d's angle is θ_c(t) exactly and
//   no unknown. The segments next to it couple their other stations to the crank as the drive
//   coupling does (−k φ − βk φ̇ in K and C, k θ_c + βk θ̇_c in r(t); their power is the input
//   work); a cam on station d is a prescribed cam, X_L(θ_c(t) − α_i), its contact row T_j, its
//   cam motion Ẋ = X_L′θ̇_c, Ẍ = X_L″θ̇_c² + X_L′θ̈_c, its force's work F_j Ẋ input work.
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
  /// The unknown of station i (−1: the prescribed drive station).
  int station_dof(int i) const { return station_dof_[std::size_t(i)]; }
  int drive_station() const { return drive_station_; }
  /// true: camshaft.drive = "prescribed" (the drive station is no unknown).
  bool prescribed() const { return prescribed_; }
  /// The crank's angle θ_c(t) [rad] and speed θ̇_c(t); with acc, its acceleration θ̈_c(t).
  void crank(double t, double* theta, double* omega, double* acc = nullptr) const;
  /// A spring–damper from the crank to an unknown: the compliant drive's coupling, or a
  /// segment next to the prescribed drive station. Its torque k(θ_c − φ) + c(θ̇_c − φ̇).
  struct Coupling {
    int dof;
    double k, c;
  };
  const std::vector<Coupling>& couplings() const { return couplings_; }
  /// Σ over the couplings of k θ_c + c θ̇_c into r (the crank's part of their forces).
  void add_crank_forcing(double t, double* r) const;
  /// The couplings' power Σ τ φ̇ at (t, q, v): with the prescribed cams' F Ẋ, the run's input.
  double coupling_power(double t, const double* q, const double* v) const;
  /// Σ over the couplings of ½kφ² and cφ̇²: the driver's, not the mechanism's.
  double coupling_energy(const double* q) const;
  double coupling_dissipation(const double* v) const;
  /// The torque the drive puts into the shaft at (t, q, v) with contact forces F (m entries):
  /// the compliant coupling's; the prescribed station's J θ̈_c + αJ θ̇_c + its segments' and its
  /// cams' reactions.
  double drive_torque(double t, const double* q, const double* v, const double* F, int m) const;
  /// Station i's angle and speed at (t, q, v) (the prescribed station's: the crank's).
  double station_angle(int i, double t, const double* q) const;
  double station_speed(int i, double t, const double* v) const;

  /// Contact j's cam (−1: not on the shaft), its station's unknown (−1: a cam on the
  /// prescribed drive station) and its cam's offset [rad].
  int contact_cam(int j) const { return std::size_t(j) < contact_cam_.size() ? contact_cam_[std::size_t(j)] : -1; }
  int contact_dof(int j) const { return station_dof(cam_station_[std::size_t(contact_cam(j))]); }
  /// Contact j rides on a cam of a station that is an unknown (its row has a shaft column).
  bool on_free_station(int j) const { return contact_cam(j) >= 0 && contact_dof(j) >= 0; }
  /// Some contact rides on a cam of a station that is an unknown: the contact rows depend on q.
  bool rows_depend_on_state() const {
    for (std::size_t j = 0; j < contact_cam_.size(); ++j)
      if (on_free_station(int(j))) return true;
    return false;
  }
  /// Contact j rides on a cam of the prescribed drive station (a prescribed cam).
  bool on_prescribed_station(int j) const { return contact_cam(j) >= 0 && contact_dof(j) < 0; }
  /// Cam i's station and offset α_i [rad].
  int cam_station(int i) const { return cam_station_[std::size_t(i)]; }
  double cam_offset(int i) const { return cam_offset_[std::size_t(i)]; }
  /// The lift of contact j's cam at the unknowns q (@pre on_free_station(j)).
  ShaftCamLift lift(int j, const double* q) const;
  /// The lift of contact j's cam at (t, q) (contact_cam(j) ≥ 0; a prescribed station's at θ_c(t)).
  ShaftCamLift lift(int j, double t, const double* q) const;
  /// Contact j's cam motion along its gap at (t, q, v): X_L, Ẋ = X_L′φ̇_s and the part of Ẍ
  /// besides X_L′φ̈_s of a free station, X_L″φ̇_s² (+ X_L′θ̈_c on the prescribed station).
  CamMotion contact_cam_motion(int j, double t, const double* q, const double* v) const;
  /// The cam angle of cam i at (t, q): φ_station − α_i [rad].
  double cam_angle(int i, double t, const double* q) const { return station_angle(cam_station(i), t, q) - cam_offset(i); }
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
  bool prescribed_ = false;
  double x_base_ = 0.0;
  double drive_inertia_ = 0.0, alpha_ = 0.0;  // the prescribed station's J and the bearing drag α
  std::vector<Coupling> couplings_;
  std::vector<double> order_, amp_, phase_;  // the crank's orders, amplitudes [rad], phases [rad]
  CamDrive drive_;
  // one Cam per cam: its evaluation tracks the contact point from the previous call
  std::vector<std::unique_ptr<Cam>> cam_;
  Eigen::MatrixXd Z_;
};

class Mechanism;

/// The natural frequencies [Hz] of a mechanism with a camshaft linearised at the unknowns q
/// with the contacts `held` closed, ascending: K̃ x = ω² M x on the null space of the held rows
/// T̃_held(q) (a held follower moves with its cam, x = X_L′φ_s), K̃ = K + Σ_held X_L″F_j e_s e_sᵀ
/// (the held forces F, m entries, on their cams' curvature), the crank held (the drive's
/// couplings are springs to ground). The shaft with its trains attached
/// (mechanism_camshaft.cpp). @pre mech.camshaft().
std::vector<double> held_frequencies_hz(const Mechanism& mech, const double* q, const std::vector<int>& held,
                                        const double* F);

/// The scene's network with the camshaft's stations, segments and bearing dampers added
/// (mechanism_camshaft.cpp). @pre scene.camshaft.present().
NetworkSpec network_with_camshaft(const Scene& scene);

}  // namespace camdyn
