// camdyn — batch runs (camdyn/batch.hpp): one Simulator per run on the shared worker pool
// (thread_pool.hpp, also run_sweep's).
#include "camdyn/batch.hpp"

#include <time.h>

#include <mutex>
#include <utility>

#include "thread_pool.hpp"

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
Summary run_one(const Scene& scene, std::vector<HistoryRow>* rows, const std::atomic<bool>* stop) {
  Summary s;
  const double c0 = thread_cpu_seconds();
  Collector c;
  c.rows = rows;
  try {
    Simulator sim(scene);
    s = sim.run(rows ? &c : nullptr, stop);
  } catch (const std::exception& e) {
    s = Summary{};
    s.scene = scene.title;
    s.finished = false;
    s.termination = dynamic_cast<const SceneError*>(&e) ? Termination::InvalidScene : Termination::Error;
    s.message = e.what();
  }
  s.cpu_seconds = thread_cpu_seconds() - c0;
  return s;
}

}  // namespace

std::vector<Summary> run_batch(const std::vector<Scene>& scenes, int threads,
                               const std::function<void(std::size_t, const Summary&)>& on_done,
                               const std::atomic<bool>* stop) {
  std::vector<Summary> out(scenes.size());
  std::mutex mu;
  detail::parallel_for(scenes.size(), threads, stop, [&](std::size_t i) {
    Summary s = run_one(scenes[i], nullptr, stop);
    std::lock_guard<std::mutex> lock(mu);
    out[i] = std::move(s);
    if (on_done) on_done(i, out[i]);
    return true;
  });
  return out;
}

std::vector<RunResult> simulate_batch(const std::vector<Scene>& scenes, int threads,
                                      const std::function<void(std::size_t, const RunResult&)>& on_done,
                                      const std::atomic<bool>* stop) {
  std::vector<RunResult> out(scenes.size());
  std::mutex mu;
  detail::parallel_for(scenes.size(), threads, stop, [&](std::size_t i) {
    RunResult r;
    r.summary = run_one(scenes[i], &r.rows, stop);
    std::lock_guard<std::mutex> lock(mu);
    out[i] = std::move(r);
    if (on_done) on_done(i, out[i]);
    return true;
  });
  return out;
}

}  // namespace camdyn
