// Engine cost per step against mesh size (elastic bar, no contact force):
//
//   M q̈ + K q = f₀,  N two-node bar elements, n = N + 1 nodes, 2n unknowns.
//
// CPU per step for N = 10², 10³, 10⁴, 10⁵ on each engine (arkode-erk, arkode-dirk with
// KLU, cvode-bdf with our KLU Schur solver). With KLU the cost must grow linearly in N.
// A plain timer program (one process, one run: ratios are measured together).
//   usage: bench_engines [max_N=100000] [steps=200]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "camdyn/model.hpp"
#include "engine.hpp"

using namespace camdyn;

int main(int argc, char** argv) {
  const long max_n = argc > 1 ? std::atol(argv[1]) : 100000;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 200;
  std::printf("%-12s %-10s %-8s %14s %14s\n", "engine", "mass", "N", "cpu_us/step", "us/step/node");
  for (Integrator integ : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
    for (MassMatrixKind mk : {MassMatrixKind::Lumped, MassMatrixKind::Consistent}) {
      for (long N = 100; N <= max_n; N *= 10) {
        Scene s;
        s.follower.kind = FollowerKind::ElasticBar;
        s.follower.elements = int(N);
        s.follower.mass_matrix = mk;
        s.solver.integrator = integ;
        s.solver.rtol = 1e-6;
        s.solver.atol = 1e-9;
        s.contact.model = integ == Integrator::CvodeBdf ? ContactModel::Event : ContactModel::Lee;
        auto model = build_model(s);
        auto eng = make_engine(model, s.solver, s.contact.model == ContactModel::Lee, s.contact.tol_u);  // no contact force
        const int n = model->n();
        Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n), y1(2 * n);
        y.head(n) = model->initial_displacement();
        y[n] = 1.0;  // a velocity kick on the contact face
        // explicit: a stable step (ω_max h ≈ 0.5); implicit: 1e-5
        const double c = std::sqrt(1e7 / (1.0 / (3.0 * 24.0)));
        const double h = integ == Integrator::ArkodeErk ? 0.5 * (24.0 / N) / (2.0 * c) : 1e-5;
        const std::clock_t c0 = std::clock();
        double t = 0;
        long taken = 0;
        if (integ == Integrator::CvodeBdf) {
          eng->reinit(0.0, y);
          for (int i = 0; i < steps; ++i) t = eng->advance(1.0, y1);
          taken = eng->stats().steps;
        } else {
          for (int i = 0; i < steps; ++i) {
            eng->step(t, y, h, y1);
            y.swap(y1);
            t += h;
          }
          taken = steps;
        }
        const double us = 1e6 * double(std::clock() - c0) / CLOCKS_PER_SEC / double(taken);
        std::printf("%-12s %-10s %-8ld %14.2f %14.5f\n", eng->name(), to_string(mk), N, us, us / double(n));
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
