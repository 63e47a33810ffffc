// camdyn — the simulator: scene → mechanism → engine + contact method → history/summary.
//
// Every follower (rigid, elastic_bar, network, your own FollowerSystem) runs as a mechanism
// with one contact method:
//   lee        Lee (1997): augmented-multiplier iteration at displacement, velocity and
//              acceleration level around each integrator step (docs/method.md §3–4).
//   penalty    spring–damper contact force inside the right-hand side.
//   holonomic  the contacts held at all times (a DAE on ida).
//   event      exact event-driven: contact / free phases switched by rootfinding.
#pragma once

#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

// The run's outputs have their own headers; included here so that this header alone
// still gives everything a run needs.
#include "camdyn/history.hpp"            // HistoryRow, ContactEvent, history_columns()
#include "camdyn/model_description.hpp"
#include "camdyn/observer.hpp"           // Observer, StepInfo, ObserverAction
#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"            // Summary and the results it holds

namespace camdyn {

class FollowerSystem;  // camdyn/follower_system.hpp

class Simulator {
 public:
  /// Validates the scene (validated(scene)), then as Simulator(ValidatedScene).
  /// @throws SceneError on an invalid scene, or an initial state that penetrates a contact
  /// by more than contact.tol_u (camdyn/initial_state.hpp, docs/initial_state.md).
  explicit Simulator(Scene scene);
  /// A scene validated already (load_validated_scene, validated): not checked again; the
  /// run's own checks (tolerances, the start state) are made.
  /// @throws SceneError on tolerances the run cannot honour or a penetrating start.
  explicit Simulator(ValidatedScene scene);
  /// Bring your own follower (camdyn/follower_system.hpp): the scene gives the cam, the
  /// contact method, the engine and the run; `follower` replaces the scene's follower
  /// (follower.*, [spring], the network tables are not used). Runs with Lee's method,
  /// penalty, event-driven or holonomic on arkode-erk, arkode-dirk, cvode-bdf.
  /// @throws SceneError on an invalid scene or follower (file "<follower>"), or an initial
  /// state that penetrates a contact (camdyn/initial_state.hpp).
  Simulator(Scene scene, std::shared_ptr<const FollowerSystem> follower);
  /// As above, the scene validated already.
  Simulator(ValidatedScene scene, std::shared_ptr<const FollowerSystem> follower);
  ~Simulator();
  /// Run to t_end. Never throws for a simulation failure: the summary says
  /// finished = false, how (termination) and why (message). `stop` (may be null) is polled each step (Ctrl-C); once it
  /// is set the run ends with finished = false, termination = StoppedByCaller and message
  /// "at t = T: <stop_reason>" (default "stopped by caller"; the CLI reports the signal
  /// that set its flag: "interrupted (SIGINT)" for Ctrl-C, "interrupted (SIGTERM)" for kill).
  Summary run(Observer* observer = nullptr, const std::atomic<bool>* stop = nullptr,
              const std::string& stop_reason = "stopped by caller");
  const Scene& scene() const { return scene_; }
  /// The model description (any follower kind).
  const ModelDescription& description() const;
  /// Names of HistoryRow::extra, in order: network scenes and user followers F_<c>, gap_<c>,
  /// in_<c> per contact c, then u_<n>, v_<n> per named node n (none for a rigid or
  /// elastic_bar follower); then the designer columns when run.designer_columns is true.
  const std::vector<std::string>& extra_columns() const { return extra_columns_; }
  /// The scene's plausibility warnings (scene_warnings(), camdyn/scene_warnings.hpp), known
  /// before the run; run() copies them into Summary::warnings.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  Scene scene_;
  std::shared_ptr<const class MechanicalSystem> mech_;  // the scene's follower, or the user's
  std::vector<std::string> extra_columns_;
  std::vector<std::string> warnings_;
  void add_designer_columns();
};

/// Convenience: run and collect all rows in memory.
struct RunResult {
  Summary summary;
  std::vector<HistoryRow> rows;
};
RunResult simulate(const Scene& scene);

}  // namespace camdyn
