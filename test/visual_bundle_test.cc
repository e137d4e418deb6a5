// A small noise-free bundle (5 keyframes, 40 landmarks, one or two cameras):
// the visual factors vanish at the truth, and Ceres, started from perturbed
// poses and inverse depths, brings them back to it.

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <memory>
#include <random>
#include <vector>

#include "factors/check/visual_scene.h"
#include "factors/pose_manifold.h"
#include "factors/reprojection_factor.h"
#include "factors/robust_kernel.h"
#include "factors/stereo_reprojection_factor.h"
#include "factors/timed_reprojection_factor.h"
#include "geometry/so3.h"

namespace vio {
namespace {

constexpr int kKeyframes = 5;
constexpr int kLandmarks = 40;
constexpr double kSqrtInfo = 458.654 / 1.5;  // EuRoC focal / sigma [-]

struct Landmark {
  Eigen::Vector3d p_w;  // [m]
  int anchor = 0;       // keyframe of the anchor observation (cam0)
  double rho = 0.0;     // true inverse depth in the anchor camera [1/m]
};

// A vehicle flying along world x with its cameras looking forward (camera z
// along world x), past a cloud of landmarks 5-12 m ahead.
struct World {
  std::vector<Block7> poses;  // T_w_b of each keyframe
  Block7 extrinsic0, extrinsic1;
  std::vector<Landmark> landmarks;

  Eigen::Isometry3d Camera(int k, int cam) const {
    return IsometryFromBlock(poses[k]) *
           IsometryFromBlock(cam == 0 ? extrinsic0 : extrinsic1);
  }
  // Normalised coordinates of landmark l in camera cam of keyframe k.
  Eigen::Vector2d Observe(int l, int k, int cam) const {
    const Eigen::Vector3d p_c = Camera(k, cam).inverse() * landmarks[l].p_w;
    return p_c.head<2>() / p_c.z();
  }
};

Eigen::Isometry3d Isometry(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

World MakeWorld(std::mt19937& rng) {
  World w;
  // EuRoC's rig: camera z along body z, image x along -body y.
  const Eigen::Matrix3d R_b_c = Exp(Eigen::Vector3d(0, 0, M_PI / 2));
  w.extrinsic0 = BlockFromIsometry(
      Isometry(R_b_c, Eigen::Vector3d(-0.022, -0.065, 0.010)));
  w.extrinsic1 = BlockFromIsometry(
      Isometry(R_b_c * Exp(Eigen::Vector3d(0.01, -0.02, 0.005)),
               Eigen::Vector3d(-0.020, 0.045, 0.008)));
  // Body z along world x, a little yaw and pitch per keyframe.
  const Eigen::Matrix3d R_w_b0 = Exp(Eigen::Vector3d(0, M_PI / 2, 0));
  for (int k = 0; k < kKeyframes; ++k) {
    const Eigen::Matrix3d R_w_b =
        Exp(Eigen::Vector3d(0.0, 0.03 * k, -0.05 * k)) * R_w_b0;
    const Eigen::Vector3d p_w_b(0.4 * k, 0.3 * std::sin(k), 0.1 * k);
    w.poses.push_back(BlockFromIsometry(Isometry(R_w_b, p_w_b)));
  }
  std::uniform_real_distribution<double> ahead(5.0, 12.0), side(-3.0, 3.0);
  while (static_cast<int>(w.landmarks.size()) < kLandmarks) {
    Landmark l;
    l.p_w = Eigen::Vector3d(ahead(rng), side(rng), side(rng));
    l.anchor = static_cast<int>(w.landmarks.size()) % 3;
    l.rho = 1.0 / (w.Camera(l.anchor, 0).inverse() * l.p_w).z();
    w.landmarks.push_back(l);
  }
  return w;
}

// The states Ceres estimates, initialised from the truth.
struct States {
  std::vector<Block7> poses;
  Block7 extrinsic0, extrinsic1;
  std::vector<double> rho;
  double t_d = 0.0;  // [s]

  explicit States(const World& w)
      : poses(w.poses), extrinsic0(w.extrinsic0), extrinsic1(w.extrinsic1) {
    for (const Landmark& l : w.landmarks) rho.push_back(l.rho);
  }
};

enum class Rig { kMono, kStereo, kMonoWithTimeOffset };

constexpr double kTrueTimeOffset = 0.004;  // [s]

// Adds every observation of every landmark as a factor. For the timed rig
// each observation gets a random image velocity, and the stored measurement
// is where the camera saw it (true_xy + t_d * velocity, frames stamped with
// t_d = 0).
void AddFactors(const World& w, Rig rig, std::mt19937& rng,
                ceres::Problem* problem, States* x) {
  std::normal_distribution<double> velocity(0.0, 0.3);  // [1/s]
  auto timed = [&](const Eigen::Vector2d& xy) {
    TimedObservation obs;
    obs.velocity = Eigen::Vector2d(velocity(rng), velocity(rng));
    obs.xy = xy + kTrueTimeOffset * obs.velocity;
    return obs;
  };
  RobustKernelOptions cauchy;
  cauchy.type = RobustKernelType::kCauchy;
  cauchy.scale = kDefaultCauchyScale;
  for (int l = 0; l < kLandmarks; ++l) {
    const int a = w.landmarks[l].anchor;
    const Eigen::Vector2d xy_a = w.Observe(l, a, 0);
    const TimedObservation obs_a = timed(xy_a);
    for (int k = 0; k < kKeyframes; ++k) {
      if (k != a && rig == Rig::kMonoWithTimeOffset) {
        problem->AddResidualBlock(
            new TimedReprojectionFactor(obs_a, timed(w.Observe(l, k, 0)),
                                        kSqrtInfo),
            nullptr, x->poses[a].data(), x->poses[k].data(),
            x->extrinsic0.data(), &x->rho[l], &x->t_d);
      } else if (k != a) {
        problem->AddResidualBlock(
            new ReprojectionFactor(xy_a, w.Observe(l, k, 0), kSqrtInfo),
            nullptr, x->poses[a].data(), x->poses[k].data(),
            x->extrinsic0.data(), &x->rho[l]);
      }
      if (rig != Rig::kStereo) continue;
      // The stereo bundle also runs the Cauchy kernel from the factory.
      if (k == a) {
        problem->AddResidualBlock(
            new StereoReprojectionFactor(xy_a, w.Observe(l, k, 1), kSqrtInfo),
            MakeLossFunction(cauchy).release(), x->extrinsic0.data(),
            x->extrinsic1.data(), &x->rho[l]);
      } else {
        problem->AddResidualBlock(new StereoTwoFrameReprojectionFactor(
                                      xy_a, w.Observe(l, k, 1), kSqrtInfo),
                                  MakeLossFunction(cauchy).release(),
                                  x->poses[a].data(), x->poses[k].data(),
                                  x->extrinsic0.data(), x->extrinsic1.data(),
                                  &x->rho[l]);
      }
    }
  }
  for (Block7* T : {&x->extrinsic0, &x->extrinsic1}) {
    if (problem->HasParameterBlock(T->data())) {
      problem->SetManifold(T->data(), new PoseManifold);
      problem->SetParameterBlockConstant(T->data());
    }
  }
  for (Block7& T : x->poses) problem->SetManifold(T.data(), new PoseManifold);
  // Gauge: the first pose; a monocular bundle also needs its scale, given by
  // one landmark's inverse depth. Stereo sees scale through the baseline.
  problem->SetParameterBlockConstant(x->poses[0].data());
  if (rig != Rig::kStereo) problem->SetParameterBlockConstant(&x->rho[0]);
}

void Perturb(std::mt19937& rng, States* x) {
  std::normal_distribution<double> dt(0.0, 0.1), dtheta(0.0, 0.03);
  std::uniform_real_distribution<double> scale(0.8, 1.2);
  for (int k = 1; k < kKeyframes; ++k) {
    Eigen::Matrix<double, 6, 1> delta;
    for (int i = 0; i < 6; ++i) delta[i] = i < 3 ? dt(rng) : dtheta(rng);
    Block7 perturbed;
    PoseManifold().Plus(x->poses[k].data(), delta.data(), perturbed.data());
    x->poses[k] = perturbed;
  }
  for (size_t l = 1; l < x->rho.size(); ++l) x->rho[l] *= scale(rng);
}

double Cost(ceres::Problem& problem) {
  double cost = 0.0;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr,
                   nullptr);
  return cost;
}

void ExpectConvergesToTruth(Rig rig) {
  std::mt19937 rng(42);
  const World w = MakeWorld(rng);
  States x(w);
  ceres::Problem problem;
  AddFactors(w, rig, rng, &problem, &x);
  // Residuals vanish at the truth (t_d at its true value).
  x.t_d = kTrueTimeOffset;
  EXPECT_LT(Cost(problem), 1e-20);

  Perturb(rng, &x);
  x.t_d = 0.0;
  const double initial_cost = Cost(problem);
  EXPECT_GT(initial_cost, 1e3);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-16;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable()) << summary.FullReport();
  EXPECT_LT(summary.final_cost, 1e-12) << summary.BriefReport();

  for (int k = 0; k < kKeyframes; ++k) {
    Eigen::Matrix<double, 6, 1> error;
    PoseManifold().Minus(x.poses[k].data(), w.poses[k].data(), error.data());
    EXPECT_LT(error.norm(), 1e-6) << "keyframe " << k;
  }
  for (int l = 0; l < kLandmarks; ++l) {
    EXPECT_NEAR(x.rho[l], w.landmarks[l].rho, 1e-6 * w.landmarks[l].rho)
        << "landmark " << l;
  }
  if (rig == Rig::kMonoWithTimeOffset) {
    EXPECT_NEAR(x.t_d, kTrueTimeOffset, 1e-9);
  }
}

TEST(VisualBundle, MonoConvergesToTruthFromPerturbedPosesAndDepths) {
  ExpectConvergesToTruth(Rig::kMono);
}

TEST(VisualBundle, StereoConvergesToTruthWithCauchyKernel) {
  ExpectConvergesToTruth(Rig::kStereo);
}

TEST(VisualBundle, MonoRecoversTimeOffsetFromImageVelocities) {
  ExpectConvergesToTruth(Rig::kMonoWithTimeOffset);
}

}  // namespace
}  // namespace vio
