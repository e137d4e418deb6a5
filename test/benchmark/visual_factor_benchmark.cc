// Evaluate (residual and every Jacobian) of each visual factor: the analytic
// factor against the same residual written as a templated functor for
// ceres::AutoDiffCostFunction, on the same random realistic states. Before
// timing, each pair is checked to agree (residuals, and Jacobians mapped to
// the tangent space). At the end a table gives autodiff CPU time / analytic
// CPU time (CPU time, because the machine may be shared).
//
//   ./build/test/benchmark/visual_factor_benchmark

#include <benchmark/benchmark.h>
#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "factors/check/factor_cases.h"
#include "factors/check/visual_scene.h"
#include "factors/inverse_depth_chain.h"
#include "factors/pose_manifold.h"

namespace vio {
namespace {

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

// p_first = R p_second + t for a 7-block [t, q(x, y, z, w)].
template <typename T>
Vec3<T> Apply(const T* x, const Vec3<T>& p) {
  const Eigen::Map<const Eigen::Quaternion<T>> q(x + 3);
  return q * p + Eigen::Map<const Vec3<T>>(x);
}
template <typename T>
Vec3<T> ApplyInverse(const T* x, const Vec3<T>& p) {
  const Eigen::Map<const Eigen::Quaternion<T>> q(x + 3);
  return q.conjugate() * (p - Eigen::Map<const Vec3<T>>(x));
}

// The homogeneous chain of factors/inverse_depth_chain.h, written plainly.
// pose_i == nullptr: one keyframe.
template <typename T>
Vec3<T> TargetPoint(const Vec3<T>& f, const T& rho, const T* T_b_a,
                    const T* pose_i, const T* pose_j, const T* T_b_c) {
  const Eigen::Map<const Eigen::Quaternion<T>> q_b_a(T_b_a + 3);
  Vec3<T> h = q_b_a * f + rho * Eigen::Map<const Vec3<T>>(T_b_a);
  if (pose_i != nullptr) {
    const Eigen::Map<const Eigen::Quaternion<T>> q_i(pose_i + 3),
        q_j(pose_j + 3);
    h = q_i * h + rho * Eigen::Map<const Vec3<T>>(pose_i);
    h = q_j.conjugate() * (h - rho * Eigen::Map<const Vec3<T>>(pose_j));
  }
  const Eigen::Map<const Eigen::Quaternion<T>> q_b_c(T_b_c + 3);
  return q_b_c.conjugate() * (h - rho * Eigen::Map<const Vec3<T>>(T_b_c));
}

template <typename T>
void Project(const Vec3<T>& h, const Eigen::Vector2d& xy, double sqrt_info,
             T* r) {
  const T z = h.z() < T(kMinProjectiveDepth) ? T(kMinProjectiveDepth) : h.z();
  r[0] = sqrt_info * (h.x() / z - xy.x());
  r[1] = sqrt_info * (h.y() / z - xy.y());
}

struct MonoFunctor {
  VisualScene s;
  template <typename T>
  bool operator()(const T* pose_i, const T* pose_j, const T* ext, const T* rho,
                  T* r) const {
    const Vec3<T> f(T(s.obs_i.xy.x()), T(s.obs_i.xy.y()), T(1.0));
    Project(TargetPoint(f, rho[0], ext, pose_i, pose_j, ext), s.obs_j.xy,
            s.sqrt_info, r);
    return true;
  }
};

struct TimedFunctor {
  VisualScene s;
  template <typename T>
  bool operator()(const T* pose_i, const T* pose_j, const T* ext, const T* rho,
                  const T* t_d, T* r) const {
    const T dt_i = t_d[0] - s.obs_i.t_d_at_stamp;
    const T dt_j = t_d[0] - s.obs_j.t_d_at_stamp;
    const Vec3<T> f(s.obs_i.xy.x() - dt_i * s.obs_i.velocity.x(),
                    s.obs_i.xy.y() - dt_i * s.obs_i.velocity.y(), T(1.0));
    const Vec3<T> h = TargetPoint(f, rho[0], ext, pose_i, pose_j, ext);
    const T z = h.z() < T(kMinProjectiveDepth) ? T(kMinProjectiveDepth) : h.z();
    r[0] = s.sqrt_info *
           (h.x() / z - (s.obs_j.xy.x() - dt_j * s.obs_j.velocity.x()));
    r[1] = s.sqrt_info *
           (h.y() / z - (s.obs_j.xy.y() - dt_j * s.obs_j.velocity.y()));
    return true;
  }
};

struct StereoSameFrameFunctor {
  VisualScene s;
  template <typename T>
  bool operator()(const T* ext0, const T* ext1, const T* rho, T* r) const {
    const Vec3<T> f(T(s.obs_i.xy.x()), T(s.obs_i.xy.y()), T(1.0));
    Project(TargetPoint<T>(f, rho[0], ext0, nullptr, nullptr, ext1), s.obs_j.xy,
            s.sqrt_info, r);
    return true;
  }
};

struct StereoTwoFrameFunctor {
  VisualScene s;
  template <typename T>
  bool operator()(const T* pose_i, const T* pose_j, const T* ext0,
                  const T* ext1, const T* rho, T* r) const {
    const Vec3<T> f(T(s.obs_i.xy.x()), T(s.obs_i.xy.y()), T(1.0));
    Project(TargetPoint(f, rho[0], ext0, pose_i, pose_j, ext1), s.obs_j.xy,
            s.sqrt_info, r);
    return true;
  }
};

// The autodiff twin of VisualFactorKinds()[kind].
std::unique_ptr<ceres::CostFunction> AutoDiffTwin(size_t kind,
                                                  const VisualScene& s) {
  switch (kind) {
    case 0:
      return std::make_unique<
          ceres::AutoDiffCostFunction<MonoFunctor, 2, 7, 7, 7, 1>>(
          new MonoFunctor{s});
    case 1:
      return std::make_unique<
          ceres::AutoDiffCostFunction<TimedFunctor, 2, 7, 7, 7, 1, 1>>(
          new TimedFunctor{s});
    case 2:
      return std::make_unique<
          ceres::AutoDiffCostFunction<StereoSameFrameFunctor, 2, 7, 7, 1>>(
          new StereoSameFrameFunctor{s});
    default:
      return std::make_unique<
          ceres::AutoDiffCostFunction<StereoTwoFrameFunctor, 2, 7, 7, 7, 7, 1>>(
          new StereoTwoFrameFunctor{s});
  }
}

// One state of one factor, ready to evaluate either way.
struct Sample {
  FactorInstance analytic;
  std::unique_ptr<ceres::CostFunction> autodiff;
  std::vector<const double*> params;
  std::vector<std::vector<double>> jacobians;  // storage, one per block
  std::vector<double*> jacobian_ptrs;
};

constexpr int kSamples = 64;

std::vector<Sample> MakeSamples(size_t kind) {
  const VisualFactorKind& k = VisualFactorKinds()[kind];
  std::mt19937 rng(42);
  std::vector<Sample> samples(kSamples);
  for (Sample& sample : samples) {
    const VisualScene s =
        SampleVisualScene(rng, VisualGeometry::kRealistic, k.target, k.timed);
    sample.analytic = k.make(s);
    sample.autodiff = AutoDiffTwin(kind, s);
    for (const auto& block : sample.analytic.blocks) {
      sample.params.push_back(block.data());
      sample.jacobians.emplace_back(2 * block.size());
    }
    for (auto& j : sample.jacobians) sample.jacobian_ptrs.push_back(j.data());
  }
  return samples;
}

// True when analytic and autodiff agree on the residual and on the tangent
// Jacobians (ambient Jacobian times PlusJacobian) of every block.
bool Agree(Sample& s) {
  double r_a[2], r_b[2];
  std::vector<std::vector<double>> j_b = s.jacobians;
  std::vector<double*> j_b_ptrs;
  for (auto& j : j_b) j_b_ptrs.push_back(j.data());
  if (!s.analytic.cost->Evaluate(s.params.data(), r_a,
                                 s.jacobian_ptrs.data()) ||
      !s.autodiff->Evaluate(s.params.data(), r_b, j_b_ptrs.data())) {
    return false;
  }
  if (std::abs(r_a[0] - r_b[0]) + std::abs(r_a[1] - r_b[1]) > 1e-9)
    return false;
  for (size_t b = 0; b < s.params.size(); ++b) {
    const int n = static_cast<int>(s.analytic.blocks[b].size());
    using M = Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::RowMajor>;
    M a = Eigen::Map<const M>(s.jacobians[b].data(), 2, n);
    M d = Eigen::Map<const M>(j_b[b].data(), 2, n);
    if (n == 7) {
      const PosePlusJacobian plus = PoseManifold::PlusJacobianAt(s.params[b]);
      a = a * plus;
      d = d * plus;
    }
    if ((a - d).cwiseAbs().maxCoeff() >
        1e-6 * (1.0 + d.cwiseAbs().maxCoeff())) {
      return false;
    }
  }
  return true;
}

void BM_Evaluate(benchmark::State& state, size_t kind, bool analytic) {
  std::vector<Sample> samples = MakeSamples(kind);
  for (Sample& s : samples) {
    if (!Agree(s)) {
      state.SkipWithError("analytic and autodiff disagree");
      return;
    }
  }
  double r[2];
  size_t i = 0;
  for (auto _ : state) {
    Sample& s = samples[i++ % samples.size()];
    const ceres::CostFunction& cost = analytic ? *s.analytic.cost : *s.autodiff;
    benchmark::DoNotOptimize(
        cost.Evaluate(s.params.data(), r, s.jacobian_ptrs.data()));
    benchmark::ClobberMemory();
  }
}

// Prints what the console reporter prints, then the ratio table.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      ns_[run.benchmark_name()] = run.GetAdjustedCPUTime();
    }
  }
  void PrintRatios() const {
    std::cout << "\nautodiff / analytic time (Evaluate with all Jacobians)\n";
    for (const VisualFactorKind& k : VisualFactorKinds()) {
      const auto a = ns_.find("analytic/" + k.name);
      const auto d = ns_.find("autodiff/" + k.name);
      if (a == ns_.end() || d == ns_.end()) continue;
      std::cout << std::left << std::setw(20) << k.name << std::right
                << std::fixed << std::setprecision(1) << std::setw(8)
                << a->second << " ns" << std::setw(10) << d->second << " ns"
                << std::setw(8) << std::setprecision(2) << d->second / a->second
                << "x\n";
    }
  }

 private:
  std::map<std::string, double> ns_;
};

}  // namespace
}  // namespace vio

int main(int argc, char** argv) {
  const auto& kinds = vio::VisualFactorKinds();
  for (size_t k = 0; k < kinds.size(); ++k) {
    benchmark::RegisterBenchmark(("analytic/" + kinds[k].name).c_str(),
                                 vio::BM_Evaluate, k, true);
    benchmark::RegisterBenchmark(("autodiff/" + kinds[k].name).c_str(),
                                 vio::BM_Evaluate, k, false);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  vio::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.PrintRatios();
  benchmark::Shutdown();
  return 0;
}
