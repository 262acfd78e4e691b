// Cost of the exact torque-free solution: one construction plus one evaluation is what a
// splitting integrator pays per step.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include "engine/exact/elliptic.hpp"
#include "engine/exact/torque_free_exact.hpp"

namespace {

using tumble::engine::TorqueFreeMotion;

const Eigen::Vector3d kMoments(1.0, 2.0, 3.0);
const Eigen::Quaterniond kOrientation(Eigen::AngleAxisd(0.7,
                                                        Eigen::Vector3d(1, 2, 3).normalized()));

// range(0): 0 = generic (m ~ 0.3), 1 = near the separatrix (m1 ~ 1e-8), 2 = symmetric body.
Eigen::Vector3d omega_for(int64_t which) {
  if (which == 1) return {1e-4, 1.0, 1e-4};
  return {1.0, 0.2, 0.3};
}
Eigen::Vector3d moments_for(int64_t which) {
  if (which == 2) return {1.0, 1.0, 3.0};
  return kMoments;
}

void BM_ConstructAndEvaluate(benchmark::State& state) {
  const Eigen::Vector3d moments = moments_for(state.range(0));
  Eigen::Vector3d omega = omega_for(state.range(0));
  const double h = 1e-3;
  for (auto _ : state) {
    const TorqueFreeMotion motion(moments, kOrientation, omega);
    const TorqueFreeMotion::State s = motion.at(h);
    benchmark::DoNotOptimize(s);
    omega.x() += 1e-12;  // a new flow each step, as after a torque kick
  }
}
BENCHMARK(BM_ConstructAndEvaluate)->Arg(0)->Arg(1)->Arg(2);

void BM_Evaluate(benchmark::State& state) {
  const TorqueFreeMotion motion(moments_for(state.range(0)), kOrientation,
                                omega_for(state.range(0)));
  double t = 0.0;
  for (auto _ : state) {
    const TorqueFreeMotion::State s = motion.at(t);
    benchmark::DoNotOptimize(s);
    t += 0.37;
  }
}
BENCHMARK(BM_Evaluate)->Arg(0)->Arg(1)->Arg(2);

void BM_JacobiElliptic(benchmark::State& state) {
  double u = 0.1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tumble::engine::jacobi_elliptic(u, 0.7, 0.3));
    u += 1e-3;
    if (u > 2.0) u = 0.1;
  }
}
BENCHMARK(BM_JacobiElliptic);

void BM_CarlsonRj(benchmark::State& state) {
  double x = 0.1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tumble::engine::carlson_rj(x, 0.5, 1.0, 3.0));
    x += 1e-3;
    if (x > 1.0) x = 0.1;
  }
}
BENCHMARK(BM_CarlsonRj);

}  // namespace

BENCHMARK_MAIN();
