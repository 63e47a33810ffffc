// camdyn — internal: the comparison set-up `camdyn bench` and its tolerance sweep share
// (bench_compare.hpp).
#include "study/bench_compare.hpp"

#include "mechanism/follower_matrices.hpp"

namespace camdyn {
namespace bench_detail {

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
  return true;
}

}  // namespace bench_detail
}  // namespace camdyn
