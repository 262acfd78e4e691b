// Cost of one step of each integrator for one body, and of the batched free-body stepper.
//
// BM_Step/<integrator>: one torque-free body with T-handle-like moments, the stepper call only
// (one iteration = one step, so the time per iteration is the time per step).
// BM_StepForced/<integrator>: the same body with gravity and an off-centre spring (force code
// on the step path; compare with BM_Step for what the force terms cost).
// BM_SimulationStep: Simulation::step for the same torque-free body with rk4 (the stepper plus
// the bookkeeping: state copy, energy and |L| checks).
// BM_BatchSemiImplicitEuler/<bodies>: one step of the structure-of-arrays batch; items per
// second = body-steps per second.
// Run with --benchmark_repetitions=5 --benchmark_report_aggregates_only=true on a shared machine
// and read the median CPU time.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <string>

#include "engine/dynamics/body_batch.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/simulation/simulation.hpp"

namespace {

using namespace tumble::engine;

// A T-handle: a light bar across a heavier handle (moments in kg m^2); spun near its
// intermediate axis, it flips.
const Eigen::Vector3d kTHandleMoments(1.3e-4, 5.0e-4, 5.9e-4);
constexpr double kStep = 1e-3;

BodyModel t_handle(bool forced) {
  BodyModel body;
  body.name = "t-handle";
  body.mass = 0.1;
  body.moments = kTHandleMoments;
  if (forced) {
    body.forces = {
        Gravity{Eigen::Vector3d(0.0, 0.0, -9.81)},
        Spring{Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d(0.02, 0.0, 0.01), 20.0, 0.0}};
  }
  return body;
}

BodyState t_handle_state(const BodyModel& body) {
  // Near the intermediate axis, ~3 rev/s.
  BodyState s = spinning_state(
      body, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized())),
      Eigen::Vector3d(0.2, 20.0, 0.2));
  s.position = Eigen::Vector3d(0.0, 0.0, 0.9);
  return s;
}

void step_loop(benchmark::State& state, IntegratorKind kind, bool forced) {
  const BodyModel body = t_handle(forced);
  const BodyState start = t_handle_state(body);
  BodyState s = start;
  const auto stepper = make_stepper(kind, body, s, StepSettings{});
  double t = 0.0;
  std::size_t steps = 0;
  for (auto _ : state) {
    stepper->step(s, t, kStep);
    t += kStep;
    benchmark::DoNotOptimize(s);
    // Back to the start every 10 s of simulated time: explicit Euler's energy growth would
    // otherwise reach Inf/NaN over millions of steps and time NaN arithmetic instead.
    if (++steps % 10000 == 0) {
      s = start;
      t = 0.0;
    }
  }
}

void BM_SimulationStep(benchmark::State& state) {
  const BodyModel body = t_handle(false);
  SimulationSettings settings;
  settings.integrator = IntegratorKind::kRk4;
  settings.dt = kStep;
  settings.duration = 1e12;  // never finishes within the benchmark
  Simulation sim({body}, {t_handle_state(body)}, settings);
  for (auto _ : state) {
    benchmark::DoNotOptimize(sim.step());
  }
}
BENCHMARK(BM_SimulationStep);

void BM_BatchSemiImplicitEuler(benchmark::State& state) {
  const auto bodies = static_cast<int>(state.range(0));
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  FreeBodyBatch batch;
  for (int i = 0; i < bodies; ++i) {
    const Eigen::Vector3d moments = kTHandleMoments * (1.0 + 0.5 * unit(random));
    BodyState s;
    s.position = Eigen::Vector3d(unit(random), unit(random), unit(random));
    s.velocity = Eigen::Vector3d(unit(random), unit(random), unit(random));
    s.orientation =
        Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized();
    s.angular_momentum =
        s.orientation *
        moments.cwiseProduct(20.0 * Eigen::Vector3d(unit(random), unit(random), unit(random)));
    batch.add(moments, s);
  }
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  for (auto _ : state) {
    step_semi_implicit_euler(batch, gravity, kStep);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * bodies);
}
BENCHMARK(BM_BatchSemiImplicitEuler)->Arg(10000);

}  // namespace

int main(int argc, char** argv) {
  // One benchmark per integrator of the catalog, torque-free and forced.
  for (const IntegratorInfo& info : integrator_catalog()) {
    const IntegratorKind kind = info.kind;
    benchmark::RegisterBenchmark(("BM_Step/" + info.name).c_str(), [kind](benchmark::State& state) {
      step_loop(state, kind, false);
    });
    if (!info.needs_torque_free) {
      benchmark::RegisterBenchmark(
          ("BM_StepForced/" + info.name).c_str(),
          [kind](benchmark::State& state) { step_loop(state, kind, true); });
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
