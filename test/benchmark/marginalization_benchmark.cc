// Cost of one marginalisation step and of one evaluation of the prior it
// leaves, at the size of a window of 10 keyframes: a previous prior over 10
// poses, 10 speed-biases (9) and one extrinsic (156 tangent coordinates), and
// N points (3, Euclidean) seen from all 10 poses. Pose 0, speed-bias 0 and the
// N points leave; the new prior covers 141 coordinates.
//
//   ./build/test/benchmark/marginalization_benchmark

#include <benchmark/benchmark.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <memory>
#include <random>
#include <vector>

#include "estimator/marginalization.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"
#include "test/testing/pose_test_factors.h"

namespace vio {
namespace {

constexpr int kWindow = 10;

struct Window {
  std::vector<std::vector<double>> poses, speed_biases, points;
  std::vector<double> extrinsic;
  std::unique_ptr<MarginalizationPrior> prior;
  std::vector<std::unique_ptr<ceres::CostFunction>> observations;
  MarginalizationProblem problem;
  PoseManifold pose_manifold;
};

std::vector<double> RandomPose(std::mt19937& rng, double spread) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Quaterniond q =
      ExpQuaternion(Eigen::Vector3d(n(rng), n(rng), n(rng)) * 0.3);
  return {spread * n(rng),
          spread * n(rng),
          spread * n(rng),
          q.x(),
          q.y(),
          q.z(),
          q.w()};
}

// A random SPD prior over all window blocks at the current values.
std::unique_ptr<MarginalizationPrior> RandomPrior(std::mt19937& rng,
                                                  const Window& w) {
  std::vector<PriorBlock> blocks;
  for (const auto& p : w.poses) blocks.push_back({PriorBlockKind::kPose, p});
  for (const auto& s : w.speed_biases) {
    blocks.push_back({PriorBlockKind::kEuclidean, s});
  }
  blocks.push_back({PriorBlockKind::kPose, w.extrinsic});
  const int n = kWindow * (6 + 9) + 6;
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
  }
  const Eigen::MatrixXd H =
      A.transpose() * A / n + 0.1 * Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd r0(n);
  for (int i = 0; i < n; ++i) r0[i] = normal(rng);
  return std::make_unique<MarginalizationPrior>(
      std::move(blocks), Eigen::MatrixXd(H.llt().matrixU()), r0);
}

std::unique_ptr<Window> MakeWindow(int num_points) {
  std::mt19937 rng(42);
  std::normal_distribution<double> n(0.0, 1.0);
  auto w = std::make_unique<Window>();
  for (int i = 0; i < kWindow; ++i) {
    w->poses.push_back(RandomPose(rng, 1.0));
    std::vector<double> sb(9);
    for (double& v : sb) v = 0.1 * n(rng);
    w->speed_biases.push_back(sb);
  }
  w->extrinsic = RandomPose(rng, 0.05);
  for (int k = 0; k < num_points; ++k) {
    w->points.push_back({5.0 * n(rng), 5.0 * n(rng), 5.0 * n(rng)});
  }
  w->prior = RandomPrior(rng, *w);

  MarginalizationProblem& problem = w->problem;
  std::vector<double*> prior_blocks;
  for (auto& p : w->poses) {
    problem.parameter_blocks.push_back({p.data(), 7, &w->pose_manifold});
    prior_blocks.push_back(p.data());
  }
  for (auto& s : w->speed_biases) {
    problem.parameter_blocks.push_back({s.data(), 9});
    prior_blocks.push_back(s.data());
  }
  problem.parameter_blocks.push_back(
      {w->extrinsic.data(), 7, &w->pose_manifold});
  prior_blocks.push_back(w->extrinsic.data());
  problem.residual_blocks.push_back({w->prior.get(), nullptr, prior_blocks});
  for (auto& l : w->points) {
    problem.parameter_blocks.push_back({l.data(), 3});
    problem.marginalized.push_back(l.data());
    for (auto& p : w->poses) {
      w->observations.push_back(std::make_unique<testing::PointTestFactor>(
          Eigen::Vector3d(n(rng), n(rng), n(rng)),
          10.0 * Eigen::Matrix3d::Identity()));
      problem.residual_blocks.push_back(
          {w->observations.back().get(), nullptr, {p.data(), l.data()}});
    }
  }
  problem.marginalized.push_back(w->poses[0].data());
  problem.marginalized.push_back(w->speed_biases[0].data());
  return w;
}

void BM_Marginalize(benchmark::State& state) {
  const auto w = MakeWindow(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const MarginalizationResult result = Marginalize(w->problem);
    if (!result.ok()) state.SkipWithError(result.message.c_str());
    benchmark::DoNotOptimize(result.jacobian.data());
  }
  state.counters["marginalised_dims"] = 6 + 9 + 3 * state.range(0);
}
BENCHMARK(BM_Marginalize)
    ->Arg(10)
    ->Arg(30)
    ->Arg(50)
    ->Unit(benchmark::kMillisecond);

// One Evaluate of the 141-row prior with all Jacobians, as the solver calls
// it once per iteration.
void BM_PriorEvaluate(benchmark::State& state) {
  const auto w = MakeWindow(30);
  const MarginalizationResult result = Marginalize(w->problem);
  if (!result.ok()) {
    state.SkipWithError(result.message.c_str());
    return;
  }
  const std::unique_ptr<MarginalizationPrior> prior = result.MakePrior();
  std::vector<const double*> params(result.kept_parameter_blocks.begin(),
                                    result.kept_parameter_blocks.end());
  std::vector<std::vector<double>> jac_storage;
  std::vector<double*> jacobians;
  for (const PriorBlock& b : prior->blocks()) {
    jac_storage.emplace_back(prior->num_residuals() * b.AmbientSize());
  }
  for (auto& j : jac_storage) jacobians.push_back(j.data());
  std::vector<double> residuals(prior->num_residuals());
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        prior->Evaluate(params.data(), residuals.data(), jacobians.data()));
  }
  state.counters["rows"] = prior->num_residuals();
}
BENCHMARK(BM_PriorEvaluate)->Unit(benchmark::kMicrosecond);

// The part of BM_Marginalize that does not depend on N: the eigen-
// decomposition of the 141 x 141 Schur complement.
void BM_SchurEigenDecomposition(benchmark::State& state) {
  const auto w = MakeWindow(10);
  const MarginalizationResult result = Marginalize(w->problem);
  for (auto _ : state) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(
        result.information);
    benchmark::DoNotOptimize(eig.eigenvalues().data());
  }
}
BENCHMARK(BM_SchurEigenDecomposition)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vio

BENCHMARK_MAIN();
