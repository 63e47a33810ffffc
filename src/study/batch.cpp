// camdyn — batch runs (camdyn/batch.hpp): one Simulator per run on the shared worker pool
// (thread_pool.hpp, also run_sweep's).
#include "camdyn/batch.hpp"

#include <time.h>

#include <memory>
#include <mutex>
#include <utility>

#include "camdyn/follower_system.hpp"
#include "study/thread_pool.hpp"

namespace camdyn {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

namespace {

struct Collector : Observer {
  std::vector<HistoryRow>* rows = nullptr;
  void on_row(const HistoryRow& r) override { rows->push_back(r); }
};

// One run of the batch: never throws (a scene that fails to build becomes its Summary).
// With a follower factory, the run uses the follower it returns (never the scene's).
const Scene& scene_of(const Scene& s) { return s; }
const Scene& scene_of(const ValidatedScene& s) { return s.scene(); }

// A ValidatedScene is not checked again (the Simulator takes it as it is).
template <class SceneT>
Summary run_one(const SceneT& scene, std::vector<HistoryRow>* rows, const std::atomic<bool>* stop,
                const FollowerFactory* follower = nullptr) {
  Summary s;
  const double c0 = thread_cpu_seconds();
  Collector c;
  c.rows = rows;
  try {
    std::unique_ptr<Simulator> sim;
    if (follower) {
      std::shared_ptr<const FollowerSystem> f = (*follower)();
      if (!f) throw SceneError("run_batch", 0, "follower", "null", "the follower factory returned no follower");
      sim = std::make_unique<Simulator>(scene, std::move(f));
    } else {
      sim = std::make_unique<Simulator>(scene);
    }
    s = sim->run(rows ? &c : nullptr, stop);
  } catch (const std::exception& e) {
    s = Summary{};
    s.scene = scene_of(scene).title;
    s.finished = false;
    s.termination = dynamic_cast<const SceneError*>(&e) ? Termination::InvalidScene : Termination::Error;
    s.message = e.what();
  }
  s.cpu_seconds = thread_cpu_seconds() - c0;
  return s;
}

void require_factory(const FollowerFactory& follower) {
  if (!follower)
    throw SceneError("run_batch", 0, "follower", "{}",
                     "the follower factory is empty (for the scenes' own followers call run_batch without one)");
}

template <class Result, class Run>
std::vector<Result> batch(std::size_t n, int threads, const std::function<void(std::size_t, const Result&)>& on_done,
                          const std::atomic<bool>* stop, const Run& run) {
  std::vector<Result> out(n);
  std::mutex mu;
  detail::parallel_for(n, threads, stop, [&](std::size_t i) {
    Result r = run(i);
    std::lock_guard<std::mutex> lock(mu);
    out[i] = std::move(r);
    if (on_done) on_done(i, out[i]);
    return true;
  });
  return out;
}

}  // namespace

std::vector<Summary> run_batch(const std::vector<Scene>& scenes, const FollowerFactory& follower, int threads,
                               const std::function<void(std::size_t, const Summary&)>& on_done,
                               const std::atomic<bool>* stop) {
  require_factory(follower);
  return batch<Summary>(scenes.size(), threads, on_done, stop,
                        [&](std::size_t i) { return run_one(scenes[i], nullptr, stop, &follower); });
}

std::vector<RunResult> simulate_batch(const std::vector<Scene>& scenes, const FollowerFactory& follower,
                                      int threads, const std::function<void(std::size_t, const RunResult&)>& on_done,
                                      const std::atomic<bool>* stop) {
  require_factory(follower);
  return batch<RunResult>(scenes.size(), threads, on_done, stop, [&](std::size_t i) {
    RunResult r;
    r.summary = run_one(scenes[i], &r.rows, stop, &follower);
    return r;
  });
}

std::vector<Summary> run_batch(const std::vector<Scene>& scenes, int threads,
                               const std::function<void(std::size_t, const Summary&)>& on_done,
                               const std::atomic<bool>* stop) {
  return batch<Summary>(scenes.size(), threads, on_done, stop,
                        [&](std::size_t i) { return run_one(scenes[i], nullptr, stop); });
}

std::vector<RunResult> simulate_batch(const std::vector<Scene>& scenes, int threads,
                                      const std::function<void(std::size_t, const RunResult&)>& on_done,
                                      const std::atomic<bool>* stop) {
  return batch<RunResult>(scenes.size(), threads, on_done, stop, [&](std::size_t i) {
    RunResult r;
    r.summary = run_one(scenes[i], &r.rows, stop);
    return r;
  });
}

std::vector<Summary> run_batch(const std::vector<ValidatedScene>& scenes, int threads,
                               const std::function<void(std::size_t, const Summary&)>& on_done,
                               const std::atomic<bool>* stop) {
  return batch<Summary>(scenes.size(), threads, on_done, stop,
                        [&](std::size_t i) { return run_one(scenes[i], nullptr, stop); });
}

}  // namespace camdyn
