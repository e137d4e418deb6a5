// One Evaluate of the IMU factor with all four Jacobians: the analytic
// ImuFactor against the same residual as a templated functor differentiated
// by ceres::AutoDiffCostFunction (test/testing/imu_residual_functor.h). Both
// run on the same random realistic state (the jacobian_check "imu" case).
//
//   ./build/test/benchmark/imu_factor_benchmark
//
// Goal: analytic at least 2x faster (compare the two Time columns).

#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "factors/check/factor_cases.h"
#include "factors/imu_factor.h"
#include "test/testing/imu_residual_functor.h"

namespace vio {
namespace {

struct Fixture {
  FactorInstance instance;
  std::vector<const double*> params;
  std::vector<std::vector<double>> jacobian_storage;
  std::vector<double*> jacobians;
  double residuals[15];

  Fixture() {
    std::mt19937 rng(42);
    instance = MakeImuFactorCase().sample(rng);
    for (const auto& b : instance.blocks) {
      params.push_back(b.data());
      jacobian_storage.emplace_back(15 * b.size());
    }
    for (auto& j : jacobian_storage) jacobians.push_back(j.data());
  }
};

void RunEvaluate(benchmark::State& state, const ceres::CostFunction& cost,
                 Fixture& f) {
  for (auto _ : state) {
    const bool ok =
        cost.Evaluate(f.params.data(), f.residuals, f.jacobians.data());
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(f.residuals);
    benchmark::ClobberMemory();
  }
}

void BM_ImuFactorAnalytic(benchmark::State& state) {
  Fixture f;
  RunEvaluate(state, *f.instance.cost, f);
}
BENCHMARK(BM_ImuFactorAnalytic);

void BM_ImuFactorAutoDiff(benchmark::State& state) {
  Fixture f;
  const auto& factor = static_cast<const ImuFactor&>(*f.instance.cost);
  const testing::ImuAutoDiffCost autodiff(new testing::ImuResidualFunctor(
      factor.preintegrated(), 9.81, factor.sqrt_information()));
  RunEvaluate(state, autodiff, f);
}
BENCHMARK(BM_ImuFactorAutoDiff);

}  // namespace
}  // namespace vio

BENCHMARK_MAIN();
