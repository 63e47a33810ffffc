// camdyn (private) — a run's CPU and wall time (Summary::cpu_seconds, wall_seconds).
#pragma once

#include <chrono>
#include <ctime>

namespace camdyn {
namespace detail {

struct Clock {
  std::clock_t c0 = std::clock();
  std::chrono::steady_clock::time_point w0 = std::chrono::steady_clock::now();
  double cpu() const { return double(std::clock() - c0) / CLOCKS_PER_SEC; }
  double wall() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count(); }
};

}  // namespace detail
}  // namespace camdyn
