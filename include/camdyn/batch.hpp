// camdyn — many runs at once: run_batch (summaries) and simulate_batch (summaries and
// history rows), on worker threads from a dynamic queue.
//
// Thread safety: each run builds its own Simulator (mechanism, Cam, engines, SUNDIALS
// context); nothing mutable is shared between runs. Cam is safe to share as well (its
// contact-point search hint is a relaxed atomic), and the scene key table is a
// function-local static initialised once.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {

/// Run every scene, `threads` at a time, from a dynamic queue (an atomic next index: a
/// slow scene does not hold up the others); the calling thread is one of the workers.
/// Runs are independent and deterministic, so every result but cpu_seconds and
/// wall_seconds is bitwise identical to Simulator(scene).run() one by one, for any
/// `threads`.
/// @param threads  worker threads; ≤ 0: std::thread::hardware_concurrency(); at most
///                 scenes.size() are started.
/// @param on_done  called as (index, summary) after each run, under a mutex (so it may
///                 write shared state); may be empty. It must not throw.
/// @param stop     may be null; polled before each run and every step of a run: once set,
///                 runs in progress end with termination = StoppedByCaller and scenes not
///                 yet started keep a default Summary (termination = Error, empty message).
/// @pre  scenes need not be resolved or valid: each is resolved and validated like
///       Simulator's constructor does. register_contact_method is not called meanwhile.
/// @return one Summary per scene, in the order of `scenes`. An invalid scene gives
///       finished = false, termination = InvalidScene and the SceneError text as message;
///       any other exception thrown while building a run, termination = Error.
///       Summary::cpu_seconds is the run's own thread CPU time.
/// @throws std::system_error if a worker thread cannot be started (nothing else: failures
///       of a run are in its Summary).
std::vector<Summary> run_batch(const std::vector<Scene>& scenes, int threads = 0,
                               const std::function<void(std::size_t, const Summary&)>& on_done = {},
                               const std::atomic<bool>* stop = nullptr);

/// As run_batch, the scenes validated already (load_validated_scene, validated): each run's
/// Simulator does not check its scene again.
std::vector<Summary> run_batch(const std::vector<ValidatedScene>& scenes, int threads = 0,
                               const std::function<void(std::size_t, const Summary&)>& on_done = {},
                               const std::atomic<bool>* stop = nullptr);

/// As run_batch, keeping every run's history rows too (RunResult, as simulate()): the
/// rows of scene i are bitwise identical to simulate(scenes[i]).rows for any `threads`.
/// Memory: all rows of all runs are held (one HistoryRow is 96 bytes).
/// Preconditions, exceptions and the meaning of threads, on_done and stop: as run_batch. A scene that
///       failed before running has no rows.
std::vector<RunResult> simulate_batch(
    const std::vector<Scene>& scenes, int threads = 0,
    const std::function<void(std::size_t, const RunResult&)>& on_done = {},
    const std::atomic<bool>* stop = nullptr);

/// A user follower (camdyn/follower_system.hpp) for many runs: called once per
/// run, on the thread that makes the run, it returns the follower of that run. Return a new
/// object per call unless the follower's const methods may be called from several threads
/// at once (then one shared object is fine). A null result is an invalid run
/// (termination = InvalidScene).
using FollowerFactory = std::function<std::shared_ptr<const FollowerSystem>()>;

/// As run_batch, every run with a user follower from `follower` instead of the scene's
/// (Simulator(scene, follower): follower.*, [spring] and the network tables are not used).
/// @throws SceneError (file "run_batch", key "follower") if `follower` is empty — the
///       scene's follower is never used silently; std::system_error as run_batch.
std::vector<Summary> run_batch(const std::vector<Scene>& scenes, const FollowerFactory& follower,
                               int threads = 0,
                               const std::function<void(std::size_t, const Summary&)>& on_done = {},
                               const std::atomic<bool>* stop = nullptr);
/// As simulate_batch, with a user follower (as the run_batch overload above).
std::vector<RunResult> simulate_batch(
    const std::vector<Scene>& scenes, const FollowerFactory& follower, int threads = 0,
    const std::function<void(std::size_t, const RunResult&)>& on_done = {},
    const std::atomic<bool>* stop = nullptr);

/// Thread CPU time of the calling thread [s] (CLOCK_THREAD_CPUTIME_ID).
double thread_cpu_seconds();

}  // namespace camdyn
