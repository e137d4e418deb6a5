// PhotometricFactor (factors/photometric_factor.h): its Jacobians against
// numeric differentiation on the synthetic case of jacobian_check and on real
// EuRoC image patches (our tangent-space check and ceres::GradientChecker),
// its residual against a closed form, the notes' weight against Monte-Carlo,
// and the inactive cases.

#include "factors/photometric_factor.h"

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "factors/check/factor_cases.h"
#include "factors/check/jacobian_check.h"
#include "factors/check/visual_scene.h"
#include "factors/pose_manifold.h"
#include "frontend/stereo_depth.h"
#include "geometry/so3.h"
#include "testing/direct_sequence.h"

namespace vio {
namespace {

Rigid ToRigid(const Eigen::Isometry3d& T) {
  return {T.linear(), T.translation()};
}

std::vector<double> Values(const Block7& x) {
  return std::vector<double>(x.data(), x.data() + x.size());
}

Eigen::Isometry3d SmallMotion(std::mt19937& rng, double angle, double dist) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Exp(Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized() * angle);
  T.translation() = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized() * dist;
  return T;
}

TEST(PhotometricFactor, JacobiansMatchNumericDiffOnTheSyntheticCase) {
  const FactorCase c = MakePhotometricCase();
  std::mt19937 rng(3);
  for (int t = 0; t < 200; ++t) {
    const FactorInstance f = c.sample(rng);
    std::vector<BlockJacobianError> errors;
    ASSERT_TRUE(CompareJacobians(f, JacobianCheckOptions(), &errors));
    for (const auto& e : errors) {
      EXPECT_LE(e.max_rel_error, c.tolerance) << e.block << " trial " << t;
    }
  }
}

// Real images: cam0 and cam1 of the first V1_01 pair, undistorted, with the
// stereo depth of the pair as the host pixels and their inverse depths.
class RealPatches : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const testing::StereoSequence seq(
        testing::SharedData("euroc_V1_01_first5s"));
    const PinholeUndistorter u0(seq.cam0), u1(seq.cam1);
    left_ = new ImagePyramid(u0.Undistort(testing::ReadGrey(seq.left[0])),
                             u0.pinhole(), 1);
    right_ = new ImagePyramid(u1.Undistort(testing::ReadGrey(seq.right[0])),
                              u1.pinhole(), 1);
    points_ = new std::vector<DepthPoint>(
        StereoInverseDepth(left_->level(0), right_->level(0), seq.T_c1_c0(), 0,
                           StereoDepthOptions()));
    T_b_c0_ = testing::ToIsometry(seq.cam0.q_b_c, seq.cam0.t_b_c);
    T_b_c1_ = testing::ToIsometry(seq.cam1.q_b_c, seq.cam1.t_b_c);
  }
  static void TearDownTestSuite() {
    delete left_;
    delete right_;
    delete points_;
  }

  // A factor from host pixel k of cam0 into cam1 of a body pose moved by a
  // few centimetres and degrees, at a random state.
  FactorInstance Instance(size_t k, std::mt19937& rng) const {
    static const auto kPose = std::make_shared<const PoseManifold>();
    const DepthPoint& p = (*points_)[k];
    const PhotometricHost host{p.uv, p.intensity, left_->level(0).camera};
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Eigen::Isometry3d T_w_bi =
        Eigen::Translation3d(u(rng), u(rng), u(rng)) *
        Eigen::Isometry3d(Exp(Eigen::Vector3d(u(rng), u(rng), u(rng))));
    const Eigen::Isometry3d T_w_bj = T_w_bi * SmallMotion(rng, 0.02, 0.03);
    FactorInstance f;
    f.cost = std::make_unique<PhotometricFactor>(
        host, right_->level(0).image, right_->level(0).camera, ToRigid(T_b_c0_),
        ToRigid(T_b_c1_), 0.3);
    f.blocks = {Values(BlockFromIsometry(T_w_bi)),
                Values(BlockFromIsometry(T_w_bj)),
                {p.rho * (1.0 + 0.1 * u(rng))},
                {0.1 * u(rng), 5.0 * u(rng)},
                {0.1 * u(rng), 5.0 * u(rng)}};
    f.manifolds = {kPose, kPose, nullptr, nullptr, nullptr};
    f.block_names = {"pose_i", "pose_j", "rho", "ab_i", "ab_j"};
    return f;
  }

  static bool Active(const FactorInstance& f) {
    std::vector<const double*> params;
    for (const auto& b : f.blocks) params.push_back(b.data());
    double r = 0.0, d = 0.0;
    return static_cast<const PhotometricFactor*>(f.cost.get())
        ->InverseDepthDerivative(params.data(), &r, &d);
  }

  static ImagePyramid* left_;
  static ImagePyramid* right_;
  static std::vector<DepthPoint>* points_;
  static Eigen::Isometry3d T_b_c0_, T_b_c1_;
};

ImagePyramid* RealPatches::left_ = nullptr;
ImagePyramid* RealPatches::right_ = nullptr;
std::vector<DepthPoint>* RealPatches::points_ = nullptr;
Eigen::Isometry3d RealPatches::T_b_c0_;
Eigen::Isometry3d RealPatches::T_b_c1_;

TEST_F(RealPatches, JacobiansMatchNumericDiffOnRealImages) {
  ASSERT_GT(points_->size(), 1000u);
  std::mt19937 rng(11);
  int checked = 0;
  double worst = 0.0;
  for (size_t k = 0; k < points_->size() && checked < 200; k += 97) {
    const FactorInstance f = Instance(k, rng);
    if (!Active(f)) continue;
    ++checked;
    std::vector<BlockJacobianError> errors;
    ASSERT_TRUE(CompareJacobians(f, JacobianCheckOptions(), &errors));
    // Bicubic interpolation is only C1: central differences straddling a
    // pixel boundary, where the real image's second derivative jumps, are
    // off by O(step * jump), a few 1e-5 of the block here (the smooth
    // synthetic case of jacobian_check meets 1e-5 with a wide margin).
    for (const auto& e : errors) {
      EXPECT_LE(e.max_rel_error, 2e-4) << e.block << " point " << k;
      worst = std::max(worst, e.max_rel_error);
    }
  }
  EXPECT_GE(checked, 150);
  RecordProperty("worst_relative_error", std::to_string(worst));
  std::printf("worst relative error over %d real patches: %.2e\n", checked,
              worst);
}

// ceres::GradientChecker as a second opinion, on the synthetic case. It
// differentiates with Ridders' extrapolation, which assumes a function smooth
// beyond its first derivative; bicubic interpolation is only C1 (its second
// derivative jumps at pixel boundaries), so the extrapolation gains nothing
// and the error is the first step's truncation: 1 % (Ceres' default) gives
// errors of order 1, 1e-4 about 1e-1, 1e-6 below 1e-4.
TEST(PhotometricFactor, GradientCheckerAgreesOnTheSyntheticCase) {
  const FactorCase c = MakePhotometricCase();
  std::mt19937 rng(12);
  for (int t = 0; t < 50; ++t) {
    const FactorInstance f = c.sample(rng);
    std::vector<const ceres::Manifold*> manifolds;
    std::vector<const double*> params;
    for (size_t b = 0; b < f.blocks.size(); ++b) {
      manifolds.push_back(f.manifolds[b].get());
      params.push_back(f.blocks[b].data());
    }
    ceres::NumericDiffOptions numeric;
    numeric.ridders_relative_initial_step_size = 1e-6;
    const ceres::GradientChecker checker(f.cost.get(), &manifolds, numeric);
    ceres::GradientChecker::ProbeResults results;
    // 1e-3: Ceres compares element by element, and a component 1e-9 of its
    // row's largest is differenced with the row's absolute error (clang -O1,
    // the sanitizer build: -9.64e-7 beside 283.8, 2.2e-10 apart, relative
    // 2.3e-4). A sign or a dropped term is off by order 1.
    EXPECT_TRUE(checker.Probe(params.data(), 1e-3, &results))
        << "trial " << t << "\n"
        << results.error_log;
  }
}

// On an image that is a linear ramp the bicubic interpolation is exact, so
// the residual has a closed form computed here with metric points.
TEST(PhotometricFactor, ResidualMatchesClosedFormOnARamp) {
  constexpr int kW = 120, kH = 90;
  std::vector<float> ramp(kW * kH);
  for (int v = 0; v < kH; ++v) {
    for (int u = 0; u < kW; ++u) ramp[v * kW + u] = 0.75f * u + 0.5f * v + 20;
  }
  const auto image = std::make_shared<const ImageGrid>(kW, kH, ramp);
  const Pinhole K{100.0, 100.0, 59.5, 44.5};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int t = 0; t < 50; ++t) {
    const Eigen::Isometry3d T_b_a = SmallMotion(rng, 1.0, 0.1);
    const Eigen::Isometry3d T_b_c = T_b_a * SmallMotion(rng, 0.02, 0.1);
    const Eigen::Isometry3d T_w_bi = SmallMotion(rng, 2.0, 3.0);
    const Eigen::Isometry3d T_w_bj = T_w_bi * SmallMotion(rng, 0.03, 0.05);
    const PhotometricHost host{
        {59.5 + 20 * u(rng), 44.5 + 15 * u(rng)}, 100.0 + 50 * u(rng), K};
    const double rho = 0.3 + 0.2 * u(rng);
    const double a_i = 0.2 * u(rng), b_i = 5 * u(rng);
    const double a_j = 0.2 * u(rng), b_j = 5 * u(rng);
    const PhotometricFactor factor(host, image, K, ToRigid(T_b_a),
                                   ToRigid(T_b_c), 0.7);
    const Block7 x_i = BlockFromIsometry(T_w_bi),
                 x_j = BlockFromIsometry(T_w_bj);
    const double ab_i[2] = {a_i, b_i}, ab_j[2] = {a_j, b_j};
    const double* params[] = {x_i.data(), x_j.data(), &rho, ab_i, ab_j};
    double r = 0.0;
    ASSERT_TRUE(factor.Evaluate(params, &r, nullptr));
    // The host pixel's point, metric, carried through the world.
    const Eigen::Vector3d p_a = K.Bearing(host.uv) / rho;
    const Eigen::Vector3d p_c =
        (T_w_bj * T_b_c).inverse() * (T_w_bi * T_b_a * p_a);
    const double w_u = K.fx * p_c.x() / p_c.z() + K.cx;
    const double w_v = K.fy * p_c.y() / p_c.z() + K.cy;
    ASSERT_TRUE(image->Inside(w_u, w_v, 2.0)) << "trial " << t;
    const double I_j = 0.75 * w_u + 0.5 * w_v + 20;
    const double f = std::exp(a_j - a_i) * (host.intensity - b_i) - (I_j - b_j);
    EXPECT_NEAR(r, 0.7 * f, 1e-9) << "trial " << t;
  }
}

// The notes' W: the variance of f when rho ~ N(rho_0, V) and both images
// carry N(0, sigma_I^2) noise is 1/W, by Monte-Carlo on real patches. V is
// small enough (about 0.1 px of image motion) for the first order to hold,
// and the points are those where the depth term is as large as the
// intensity term or larger.
TEST_F(RealPatches, WeightIsTheInverseVarianceOfTheResidual) {
  std::mt19937 rng(21);
  std::normal_distribution<double> n(0.0, 1.0);
  constexpr double kSigmaI = 1.0;      // [grey]
  constexpr double kSigmaRho = 0.002;  // [1/m]: ~0.1 px on this rig
  int checked = 0;
  for (size_t k = 7; k < points_->size() && checked < 20; k += 211) {
    FactorInstance f = Instance(k, rng);
    std::vector<const double*> params;
    for (const auto& b : f.blocks) params.push_back(b.data());
    const auto* factor = static_cast<const PhotometricFactor*>(f.cost.get());
    double f0 = 0.0, d_f_d_rho = 0.0;
    if (!factor->InverseDepthDerivative(params.data(), &f0, &d_f_d_rho) ||
        std::abs(d_f_d_rho) * kSigmaRho < kSigmaI) {
      continue;
    }
    ++checked;
    const double W =
        PhotometricWeight(kSigmaI, d_f_d_rho, kSigmaRho * kSigmaRho);
    double sum = 0.0, sum2 = 0.0;
    constexpr int kSamples = 20000;
    for (int s = 0; s < kSamples; ++s) {
      double rho = f.blocks[2][0] + kSigmaRho * n(rng);
      std::vector<const double*> p = params;
      p[2] = &rho;
      double fs = 0.0, unused = 0.0;
      ASSERT_TRUE(factor->InverseDepthDerivative(p.data(), &fs, &unused));
      fs += kSigmaI * (n(rng) - n(rng));  // noise of I_i and of I_j
      sum += fs;
      sum2 += fs * fs;
    }
    const double var = sum2 / kSamples - std::pow(sum / kSamples, 2);
    EXPECT_NEAR(var * W, 1.0, 0.1) << "point " << k;
  }
  EXPECT_GE(checked, 10);
}

TEST(PhotometricFactor, OutsideTheImageOrBehindTheCameraIsInactive) {
  std::vector<float> values(40 * 30, 100.0f);
  const auto image = std::make_shared<const ImageGrid>(40, 30, values);
  const Pinhole K{40.0, 40.0, 19.5, 14.5};
  const PhotometricFactor factor({{19.5, 14.5}, 90.0, K}, image, K,
                                 ToRigid(Eigen::Isometry3d::Identity()),
                                 ToRigid(Eigen::Isometry3d::Identity()), 1.0);
  Block7 x_i = BlockFromIsometry(Eigen::Isometry3d::Identity());
  double ab[2] = {0.0, 0.0};
  double rho = 1.0;
  // (a) Moved sideways by 2 m: the point leaves the 40 x 30 image.
  // (b) Turned around: the point is behind the target camera.
  Eigen::Isometry3d away = Eigen::Isometry3d::Identity();
  away.translation() = Eigen::Vector3d(2.0, 0.0, 0.0);
  Eigen::Isometry3d behind = Eigen::Isometry3d::Identity();
  behind.linear() = Exp(Eigen::Vector3d(0.0, M_PI, 0.0));
  for (const Eigen::Isometry3d& T : {away, behind}) {
    Block7 x_j = BlockFromIsometry(T);
    const double* params[] = {x_i.data(), x_j.data(), &rho, ab, ab};
    double r = 1.0;
    std::vector<double> J0(7, 1.0), J1(7, 1.0), J2(1, 1.0), J3(2, 1.0),
        J4(2, 1.0);
    double* jacobians[] = {J0.data(), J1.data(), J2.data(), J3.data(),
                           J4.data()};
    ASSERT_TRUE(factor.Evaluate(params, &r, jacobians));
    EXPECT_EQ(r, 0.0);
    for (const auto* J : {&J0, &J1, &J2, &J3, &J4}) {
      for (double v : *J) EXPECT_EQ(v, 0.0);
    }
  }
  // Non-finite input fails the evaluation.
  double nan_rho = std::nan("");
  const double* params[] = {x_i.data(), x_i.data(), &nan_rho, ab, ab};
  double r = 0.0;
  EXPECT_FALSE(factor.Evaluate(params, &r, nullptr));
}

TEST(ImageGrid, InterpolatesTheStoredValuesAndRejectsBadSizes) {
  std::vector<float> values(8 * 6);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 3.0f * i;
  const ImageGrid grid(8, 6, values);
  EXPECT_DOUBLE_EQ(grid.Value(3, 2), grid.At(3, 2));
  double I, du, dv;
  grid.Evaluate(3.5, 2.5, &I, &du, &dv);  // a ramp: 3 per column, 24 per row
  EXPECT_NEAR(I, 3.0 * (2.5 * 8 + 3.5), 1e-9);
  EXPECT_NEAR(du, 3.0, 1e-9);
  EXPECT_NEAR(dv, 24.0, 1e-9);
  EXPECT_TRUE(grid.Inside(2.0, 2.0, 2.0));
  EXPECT_FALSE(grid.Inside(5.5, 2.0, 2.0));
  EXPECT_FALSE(grid.Inside(std::nan(""), 2.0, 0.0));
  EXPECT_THROW(ImageGrid(8, 6, std::vector<float>(47)), std::invalid_argument);
  EXPECT_THROW(ImageGrid(3, 6, std::vector<float>(18)), std::invalid_argument);
}

}  // namespace
}  // namespace vio
