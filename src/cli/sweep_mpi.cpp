// camdyn CLI — `camdyn sweep` under mpirun (see sweep_mpi.hpp).
#include "sweep_mpi.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

#ifdef CAMDYN_WITH_MPI
// The C API only (the deprecated C++ bindings' header does not compile warning-free).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "camdyn/output.hpp"
#endif

namespace camdyn_cli {

int mpi_rank_from_env() {
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}) {
    const char* s = std::getenv(v);
    if (s && *s) return std::atoi(s);
  }
  return 0;
}

bool launched_under_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    const char* s = std::getenv(v);
    if (s && std::atol(s) > 1) return true;
  }
  return false;
}

#ifndef CAMDYN_WITH_MPI

bool mpi_available() { return false; }

camdyn::SweepResult run_sweep_mpi(const camdyn::Scene&, const camdyn::SweepOptions&, bool*) {
  throw camdyn::SceneError("mpirun", 0, "mpi", "launched with several ranks",
                           "this camdyn was built without MPI (CMake option CAMDYN_WITH_MPI=OFF or "
                           "no MPI found): run it without mpirun, or rebuild with libopenmpi-dev");
}

#else

bool mpi_available() { return true; }

namespace {
constexpr int kTagResult = 1;  // worker → master: a point's journal text ("" = ready)
constexpr int kTagWork = 2;    // master → worker: a point index, −1 = stop

struct MpiSession {
  MpiSession() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  }
  ~MpiSession() { MPI_Finalize(); }
};
}  // namespace

camdyn::SweepResult run_sweep_mpi(const camdyn::Scene& base, const camdyn::SweepOptions& o,
                                  bool* is_master) {
  using namespace camdyn;
  MpiSession session;
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  *is_master = rank == 0;
  // Every rank plans the same sweep from the same command line (bad input fails on every
  // rank alike, before any message is exchanged).
  const SweepPlan plan = plan_sweep(base, o);
  SweepResult res;
  res.total = plan.total;

  if (rank != 0) {
    // Wait for the master's journal to be ready (it may refuse a --resume).
    int ok = 0;
    MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!ok) return res;
    std::string block;  // empty: "ready"
    for (;;) {
      MPI_Send(block.data(), static_cast<int>(block.size()), MPI_CHAR, 0, kTagResult, MPI_COMM_WORLD);
      long idx = -1;
      MPI_Recv(&idx, 1, MPI_LONG, 0, kTagWork, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (idx < 0) break;
      block = run_sweep_point(plan, idx, o.timing, o.point_timeout_seconds, o.stop);
      ++res.computed;
    }
    return res;
  }

  // ---- master
  std::unique_ptr<SweepJournal> journal;
  std::unique_ptr<SceneError> bad_input;
  std::string setup_error;
  try {
    ensure_output_dir(o.out_dir);
    journal = std::make_unique<SweepJournal>(plan, o.out_dir, o.resume);
  } catch (const SceneError& e) {
    bad_input = std::make_unique<SceneError>(e);
  } catch (const std::exception& e) {
    setup_error = e.what();
  }
  int ok = journal ? 1 : 0;
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!ok) {
    if (bad_input) throw *bad_input;
    throw std::runtime_error(setup_error);
  }
  res.skipped = journal->done_count();
  std::vector<long> todo;
  for (long i = 0; i < plan.total; ++i)
    if (!journal->done(i)) todo.push_back(i);
  std::atomic<std::size_t> next{0};
  std::mutex mu;
  std::string io_error;
  const auto w0 = std::chrono::steady_clock::now();
  auto deliver = [&](const std::string& block) {
    if (block.empty()) return;
    std::lock_guard<std::mutex> lock(mu);
    try {
      journal->append(block);
      ++res.computed;
    } catch (const std::exception& e) {
      io_error = e.what();
    }
    if (o.progress)
      o.progress(journal->done_count(), plan.total, journal->failed_count(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
  };
  auto stopped = [&] { return (o.stop && o.stop->load()) || !io_error.empty(); };
  // Rank 0 computes too, on its own thread (no MPI calls there: MPI_THREAD_FUNNELED).
  std::thread local([&] {
    for (;;) {
      if (stopped()) return;
      const std::size_t k = next.fetch_add(1);
      if (k >= todo.size()) return;
      const std::string block = run_sweep_point(plan, todo[k], o.timing, o.point_timeout_seconds, o.stop);
      if (block.empty()) return;
      deliver(block);
    }
  });
  int active = size - 1;
  std::vector<char> buf;
  while (active > 0) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagResult, MPI_COMM_WORLD, &flag, &st);
    if (!flag) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    int count = 0;
    MPI_Get_count(&st, MPI_CHAR, &count);
    buf.resize(static_cast<std::size_t>(count) + 1);
    MPI_Recv(buf.data(), count, MPI_CHAR, st.MPI_SOURCE, kTagResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    deliver(std::string(buf.data(), static_cast<std::size_t>(count)));
    long idx = -1;
    if (!stopped()) {
      const std::size_t k = next.fetch_add(1);
      if (k < todo.size()) idx = todo[k];
    }
    if (idx < 0) --active;
    MPI_Send(&idx, 1, MPI_LONG, st.MPI_SOURCE, kTagWork, MPI_COMM_WORLD);
  }
  local.join();
  if (!io_error.empty()) throw std::runtime_error(io_error);
  res.failed = journal->failed_count();
  res.interrupted = journal->done_count() < plan.total;
  journal->write_outputs();
  res.csv_path = join_path(o.out_dir, "sweep.csv");
  res.poincare_path = join_path(o.out_dir, "poincare.csv");
  return res;
}

#endif

}  // namespace camdyn_cli
