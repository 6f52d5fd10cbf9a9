// Per-call time of the C API (include/railwear/railwear.h) as a vehicle-dynamics code calls it
// per time step: rw_set_state + rw_calculate on a handle set up once (issue 20).
//   BM_GaugeCornerWheel/<accuracy>: S1002 on UIC60 1:40 with the flange root at the gauge
//     corner (lateral -5.6 mm, no yaw: two patches, the gauge corner's at 16.5 degrees and the
//     tread's at 7 degrees), 100 kN, rolling at 20 m/s, FASTSIM tractions, conformal model;
//     accuracy 0 draft .. 3 fine. The counter `patches` shows the two.
//   BM_GaugeCornerWheelNewPosition/<accuracy>: the same at a new lateral position every call
//     (0.1 um apart, as BM_TreadFastsimNewPosition): what a co-simulation's time loop pays there;
//     accuracy 0 draft, 1 standard.
//   BM_GaugeCornerWheelTimeStep/<warm>: the gauge-corner wheel at standard accuracy stepped as
//     an MBS time loop does, +0.01 mm per call from -5.6 mm, wrapping back after 40 calls
//     (0.4 mm); warm 0 every call cold, 1 rw_set_warm_start (API 1.5: each call starts from the
//     last one's measured patch, core/contact/contact_warm_start.h).
//   BM_WheelsetGaugeCornerTimeStep/<warm>: a wheelset of those wheels stepped the same way,
//     displaced +0.01 mm per call from 4.9 mm toward the right rail (its right wheel on the gauge
//     corner, the left one on its rail's crown), standard; warm 0 cold, 1 both wheels warm.
//   BM_TreadFastsim/<model>: the same wheel on its tread (-10.4 mm, 5 mrad of yaw), the cheapest
//     rolling call: draft accuracy, model 1 halfspace (planar Boussinesq grid), 4 auto.
//   The handle keeps the placed geometry of its last call and reuses it at the same pose
//   (core/contact/placement_cache.h), as in the rows above (one state, called again and again).
//   Two rows show what that reuse is worth in a time loop:
//   BM_TreadFastsimNewVelocity/<model>: the same position, a new lateral velocity every call
//     (an implicit integrator's creep-damping derivative, or a step re-solved at one position):
//     the placement is reused.
//   BM_TreadFastsimNewPosition/<model>: a new lateral position every call (0.1 um apart, the
//     next time step of a co-simulation): every call places the wheel again.
//   BM_TreadFastsimNewPosition/0 is RW_MODEL_HERTZ there: at -10.4 mm the patch is not Hertzian
//     (the crown's 300 mm radius meets the 80 mm one inside it), so the fast tread path
//     (core/contact/hertz_tread.h) falls back to kind auto: the check's cost on top of auto's.
//   BM_CrownNewPosition/<model>/<accuracy>: the same wheel at -20 mm, 5 mrad (on the rail's
//     crown, one Hertzian patch), a new lateral position every call: model 0 RW_MODEL_HERTZ (the
//     fast tread path), 1 halfspace, 4 auto; accuracy 0 draft, 1 standard.
//   BM_WheelsetTreadNewPosition/<model>: a wheelset of those wheels displaced 4 mm to the left,
//     1 mrad (the right wheel on the crown at -14.5 mm, the left one on the 80 mm radius at
//     -6.5 mm: both single Hertzian patches), draft, a new displacement every call: model 0
//     RW_MODEL_HERTZ (both wheels on the fast tread path, API 1.4), 1 halfspace, 4 auto.
// Run: build/tests/benchmarks/api_bench --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "railwear/railwear.h"
#include "tests/api/rolling_wheel.h"

namespace {

// BM_GaugeCornerWheelTimeStep's steps before it wraps to its first position.
constexpr long kTimeSteps = 40;

rw_state State(double lateral_m, double yaw_rad) {
  return railwear::test::RollingState(lateral_m, yaw_rad);
}

// Calls `next(k)` for the k-th call's state, then rw_set_state and rw_calculate.
template <class Next>
void RunChangingSteps(benchmark::State& state, rw_problem* p, Next next) {
  int patches = 0;
  long k = 0;
  for (auto _ : state) {
    const rw_state s = next(k++);
    rw_set_state(p, &s);
    if (rw_calculate(p) != RW_OK) {
      state.SkipWithError(rw_last_error(p));
      break;
    }
    rw_get_patch_count(p, &patches);
    benchmark::DoNotOptimize(patches);
  }
  state.counters["patches"] = patches;
  rw_destroy(p);
}

// The same state every call.
void RunSteps(benchmark::State& state, rw_problem* p, const rw_state& s) {
  RunChangingSteps(state, p, [&](long) { return s; });
}

void BM_GaugeCornerWheel(benchmark::State& state) {
  RunSteps(
      state,
      railwear::test::MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, static_cast<int>(state.range(0))),
      State(-5.6e-3, 0.0));
}
BENCHMARK(BM_GaugeCornerWheel)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

void BM_GaugeCornerWheelNewPosition(benchmark::State& state) {
  RunChangingSteps(
      state,
      railwear::test::MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, static_cast<int>(state.range(0))),
      [](long k) { return State(-5.6e-3 + 1e-7 * static_cast<double>(k % 16), 0.0); });
}
BENCHMARK(BM_GaugeCornerWheelNewPosition)->DenseRange(0, 1)->Unit(benchmark::kMillisecond);

void BM_GaugeCornerWheelTimeStep(benchmark::State& state) {
  rw_problem* p = railwear::test::MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, RW_ACCURACY_STANDARD);
  if (p && state.range(0) == 1) rw_set_warm_start(p, 1);
  RunChangingSteps(state, p, [](long k) {
    return State(-5.6e-3 + 1e-5 * static_cast<double>(k % kTimeSteps), 0.0);
  });
}
// The time-step rows run kTimeSteps calls per repetition, each position once: with a run time
// instead, a faster library ran more calls, further along the steps, whose cost varies tenfold
// (cold: 15-38 ms of CPU from -5.60 to -5.37 mm, 199-283 ms from -5.35 to -5.21 mm, main at
// b23757c, tests/benchmarks/cold_call_positions.py; docs/library.md, "The cold call"), so the
// medians of two libraries compared different positions.
BENCHMARK(BM_GaugeCornerWheelTimeStep)
    ->DenseRange(0, 1)
    ->Iterations(kTimeSteps)
    ->Unit(benchmark::kMillisecond);

void BM_WheelsetGaugeCornerTimeStep(benchmark::State& state) {
  rw_problem* p = railwear::test::MakeRollingS1002Wheel(RW_MODEL_CONFORMAL, RW_ACCURACY_STANDARD,
                                                        RW_PROBLEM_WHEELSET);
  if (p && state.range(0) == 1) rw_set_warm_start(p, 1);
  RunChangingSteps(state, p, [](long k) {
    return State(4.9e-3 + 1e-5 * static_cast<double>(k % kTimeSteps), 0.0);
  });
}
BENCHMARK(BM_WheelsetGaugeCornerTimeStep)
    ->DenseRange(0, 1)
    ->Iterations(kTimeSteps)
    ->Unit(benchmark::kMillisecond);

void BM_TreadFastsim(benchmark::State& state) {
  RunSteps(
      state,
      railwear::test::MakeRollingS1002Wheel(static_cast<int>(state.range(0)), RW_ACCURACY_DRAFT),
      State(-10.4e-3, 5e-3));
}
BENCHMARK(BM_TreadFastsim)
    ->Arg(RW_MODEL_HALFSPACE)
    ->Arg(RW_MODEL_AUTO)
    ->Unit(benchmark::kMicrosecond);

void BM_TreadFastsimNewVelocity(benchmark::State& state) {
  RunChangingSteps(
      state,
      railwear::test::MakeRollingS1002Wheel(static_cast<int>(state.range(0)), RW_ACCURACY_DRAFT),
      [](long k) {
        rw_state s = State(-10.4e-3, 5e-3);
        s.lateral_velocity_m_s = 1e-3 * static_cast<double>(k % 16);
        return s;
      });
}
BENCHMARK(BM_TreadFastsimNewVelocity)
    ->Arg(RW_MODEL_HALFSPACE)
    ->Arg(RW_MODEL_AUTO)
    ->Unit(benchmark::kMicrosecond);

void BM_TreadFastsimNewPosition(benchmark::State& state) {
  RunChangingSteps(
      state,
      railwear::test::MakeRollingS1002Wheel(static_cast<int>(state.range(0)), RW_ACCURACY_DRAFT),
      [](long k) { return State(-10.4e-3 + 1e-7 * static_cast<double>(k % 16), 5e-3); });
}
BENCHMARK(BM_TreadFastsimNewPosition)
    ->Arg(RW_MODEL_HERTZ)
    ->Arg(RW_MODEL_HALFSPACE)
    ->Arg(RW_MODEL_AUTO)
    ->Unit(benchmark::kMicrosecond);

void BM_CrownNewPosition(benchmark::State& state) {
  RunChangingSteps(state,
                   railwear::test::MakeRollingS1002Wheel(static_cast<int>(state.range(0)),
                                                         static_cast<int>(state.range(1))),
                   [](long k) { return State(-20e-3 + 1e-7 * static_cast<double>(k % 16), 5e-3); });
}
BENCHMARK(BM_CrownNewPosition)
    ->Args({RW_MODEL_HERTZ, RW_ACCURACY_DRAFT})
    ->Args({RW_MODEL_HERTZ, RW_ACCURACY_STANDARD})
    ->Args({RW_MODEL_HALFSPACE, RW_ACCURACY_DRAFT})
    ->Args({RW_MODEL_AUTO, RW_ACCURACY_DRAFT})
    ->Unit(benchmark::kMicrosecond);

void BM_WheelsetTreadNewPosition(benchmark::State& state) {
  RunChangingSteps(state,
                   railwear::test::MakeRollingS1002Wheel(static_cast<int>(state.range(0)),
                                                         RW_ACCURACY_DRAFT, RW_PROBLEM_WHEELSET),
                   [](long k) { return State(-4e-3 + 1e-7 * static_cast<double>(k % 16), 1e-3); });
}
BENCHMARK(BM_WheelsetTreadNewPosition)
    ->Arg(RW_MODEL_HERTZ)
    ->Arg(RW_MODEL_HALFSPACE)
    ->Arg(RW_MODEL_AUTO)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
