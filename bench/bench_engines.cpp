// Engine cost per step against mesh size (elastic bar, no contact force):
//
//   M q̈ + K q = f₀,  N two-node bar elements, n = N + 1 nodes, 2n unknowns.
//
// CPU per step for N = 10², 10³, 10⁴, 10⁵ on each engine of the mechanism (arkode-erk,
// arkode-dirk and cvode-bdf with the sparse Schur complement on KLU, src/engine/ode_engine.cpp).
// With KLU the cost must grow linearly in N.
// A plain timer program (one process, one run: ratios are measured together).
//   usage: bench_engines [max_N=100000] [steps=200]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include <algorithm>
#include <memory>

#include "mechanism/mechanism.hpp"
#include "engine/ode_engine.hpp"

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
        // The bar as a one-contact mechanism (src/mechanism/follower_builder.cpp) on the engines
        // every method runs on (src/engine/ode_engine.cpp), no contact force.
        const Mechanism mech(s);
        const int n = mech.n();
        OdeSystem sys;
        sys.size = 2 * n;
        sys.rhs = [&mech, n](double t, const double* y, double* yd) {
          std::copy(y + n, y + 2 * n, yd);
          mech.acceleration(t, y, y + n, Eigen::VectorXd(), yd + n);
        };
        auto sn = std::make_shared<SparseNewton>();
        sn->M = &mech.M();
        sn->K = &mech.K();
        sn->C = mech.damped() ? &mech.C() : nullptr;
        sn->T = mech.T();
        sys.newton = sn;
        sys.linear = true;
        sys.max_order = 2;  // an undamped bar (as the methods' policy, methods/event.cpp)
        const bool native = integ == Integrator::CvodeBdf;
        auto eng = OdeEngine::make(integ, s.solver, sys, /*trial=*/!native);
        Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n), y1(2 * n);
        y.head(n) = mech.q0();
        y[n] = 1.0;  // a velocity kick on the contact face
        // explicit: a stable step (ω_max h ≈ 0.5); implicit: 1e-5
        const double c = std::sqrt(1e7 / (1.0 / (3.0 * 24.0)));
        const double h = integ == Integrator::ArkodeErk ? 0.5 * (24.0 / N) / (2.0 * c) : 1e-5;
        const std::clock_t c0 = std::clock();
        double t = 0;
        long taken = 0;
        if (native) {
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
