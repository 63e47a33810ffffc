// camdyn — internal: the comparison set-up `camdyn bench` and its tolerance sweep share
// (bench_compare.hpp).
#include "study/bench_compare.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cinttypes>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "camdyn/scene.hpp"
#include "mechanism/follower_matrices.hpp"

namespace camdyn {
namespace bench_detail {

namespace {

std::string cache_key(const Scene& ref) {
  std::string text = to_toml(ref) + "\nversion " CAMDYN_BENCH_VERSION "\n";
  struct stat st {};
  if (::stat("/proc/self/exe", &st) == 0)
    text += "exe " + std::to_string(long(st.st_size)) + " " + std::to_string(long(st.st_mtime)) + "\n";
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (unsigned char ch : text) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  char b[32];
  std::snprintf(b, sizeof b, "%016" PRIx64, h);
  return b;
}

bool load_run(const std::string& path, Run& r) {
  std::ifstream f(path);
  if (!f) return false;
  std::string magic;
  long nrows = 0, nev = 0, fin = 0;
  if (!(f >> magic >> fin >> r.sum.separations >> r.sum.cpu_seconds >> r.sum.steps >> r.sum.rhs_evals >>
        r.sum.rejected_steps >> r.sum.lin_setups >> r.sum.nonlin_iters >> r.sum.nonlin_conv_fails >>
        r.sum.err_test_fails >> nrows >> nev) ||
      magic != "camdyn-bench-reference-3" || nrows < 0 || nev < 0)
    return false;
  r.sum.finished = fin != 0;
  r.rows.resize(size_t(nrows));
  for (auto& row : r.rows)
    if (!(f >> row.t >> row.u_c >> row.v_c >> row.contact_force >> row.in_contact)) return false;
  r.events.resize(size_t(nev));
  for (auto& e : r.events) {
    int type = 0;
    if (!(f >> e.t >> type >> e.impact_velocity >> e.impulse)) return false;
    e.type = static_cast<EventKind>(type);
  }
  std::getline(f >> std::ws, r.sum.message);
  r.sum.termination = r.sum.finished ? Termination::Finished : Termination::Error;
  return true;
}

void save_run(const std::string& path, const Run& r) {
  std::ostringstream o;
  o.precision(17);
  o << "camdyn-bench-reference-3 " << (r.sum.finished ? 1 : 0) << " " << r.sum.separations << " "
    << r.sum.cpu_seconds << " " << r.sum.steps << " " << r.sum.rhs_evals << " " << r.sum.rejected_steps << " "
    << r.sum.lin_setups << " " << r.sum.nonlin_iters << " " << r.sum.nonlin_conv_fails << " "
    << r.sum.err_test_fails << " " << r.rows.size() << " "
    << r.events.size() << "\n";
  for (const auto& row : r.rows)
    o << row.t << " " << row.u_c << " " << row.v_c << " " << row.contact_force << " " << row.in_contact << "\n";
  for (const auto& e : r.events)
    o << e.t << " " << int(e.type) << " " << e.impact_velocity << " " << e.impulse << "\n";
  o << r.sum.message << "\n";
  const std::string tmp = path + ".tmp" + std::to_string(long(::getpid()));
  {
    std::ofstream f(tmp);
    f << o.str();
    if (!f) return;  // a cache that cannot be written is no error: the run is not cached
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace

Run reference_run(const Scene& ref, const std::string& dir, bool* cached) {
  if (cached) *cached = false;
  std::string path;
  if (!dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    path = (std::filesystem::path(dir) / ("ref-" + cache_key(ref) + ".txt")).string();
    Run r;
    if (load_run(path, r)) {
      if (cached) *cached = true;
      return r;
    }
  }
  Run r = run_once(ref, 0.0, true);
  if (!path.empty() && r.sum.finished) save_run(path, r);
  return r;
}

/// An elastic bar whose element crossing time h_e / c (c = √(E/ρ), ρ = m / (A L)) is below
/// 2 µs: the stability bound of an explicit step (the reference's, arkode-erk's) and every
/// engine's cost per simulated second scale with it (the stiff bar 0.63 µs, B1 on 1000
/// elements 0.89 µs, B1 and B2 22 µs).
bool fine_mesh_bar(const FollowerSpec& f) {
  if (!(f.elements > 0 && f.mass > 0 && f.area > 0 && f.length > 0 && f.youngs_modulus > 0))
    return false;
  const double rho = f.mass / (f.area * f.length);
  return (f.length / f.elements) / std::sqrt(f.youngs_modulus / rho) < 2e-6;
}

bool setup_scene_info(SceneInfo& si, const Scene& base, const Run& rr, double dt) {
  si.rigid = base.follower.kind == FollowerKind::Rigid;
  si.jumps = rr.sum.separations > 0;
  si.dt = dt;
  si.scene = base;
  si.scene.run.output_dt = dt;
  if (si.rigid) {
    const FollowerMatrices f = follower_matrices(si.scene);
    si.m = f.M.coeff(0, 0);
    si.k = f.K.coeff(0, 0);
    si.c = f.C.size() > 0 ? f.C.coeff(0, 0) : 0.0;
    si.f0 = f.f0[0];
  }
  si.n = size_t(std::floor(base.run.t_end / dt + 1e-9)) + 1;
  si.k_window = std::max<size_t>(1, size_t(std::lround(1e-3 / dt)));
  const double rev_s = base.cam.speed_table_rev_s.empty() ? base.cam.speed_rev_s : 0.0;
  si.k_rev = rev_s != 0 ? size_t(std::lround(1.0 / std::fabs(rev_s) / dt)) : 0;
  si.k_point = si.n - 1;
  si.ref = to_grid(rr.rows, dt, si.n);
  add_kicks(si.ref, rr.events, dt);
  if (!rr.sum.finished || !complete(si.ref)) return false;
  si.chaotic = !si.rigid && rr.sum.separations > 0;
  if (si.chaotic && si.k_rev > 0) si.k_point = std::min(si.n - 1, si.k_rev);
  si.ref_events = switch_events(rr.events, dt * double(si.k_point));
  long in = 0;
  for (size_t k = 0; k < si.n; ++k) in += si.ref.c[k] ? 1 : 0;
  si.ref_contact_frac = double(in) / double(si.n);
  double fsum = 0;
  long fn = 0;
  for (size_t k = 0; k < si.n; ++k)
    if (si.ref.f[k] > 0) {
      fsum += si.ref.f[k];
      ++fn;
    }
  si.ref_mean_force = fn ? fsum / double(fn) : kNaN;
  return true;
}

}  // namespace bench_detail
}  // namespace camdyn
