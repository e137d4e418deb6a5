#include "dataset/imu_curve_terms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>
#include <string>
#include <utility>

#include "geometry/so3.h"

namespace vio {
namespace {

// 12 control points 0.05 s apart with rotations far from each other (up to
// about 0.6 rad between neighbours), two random bias knots 0.2 s apart.
ImuCurveState RandomState() {
  std::mt19937 rng(42);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto gaussian = [&](double s) {
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    return Eigen::Vector3d(s * x, s * y, s * z);
  };
  ImuCurveState state;
  state.knot_spacing_s = 0.05;
  state.bias_knot_spacing_s = 0.2;
  Eigen::Quaterniond q = ExpQuaternion(gaussian(1.0));
  for (int i = 0; i < 12; ++i) {
    state.positions.push_back(gaussian(1.0));
    q = q * ExpQuaternion(gaussian(0.3));
    state.rotations.push_back(q);
  }
  for (int m = 0; m < 4; ++m) {
    state.b_g.push_back(gaussian(0.01));
    state.b_a.push_back(gaussian(0.1));
  }
  return state;
}

using TermOf = std::function<CurveTerm(const ImuCurveState&)>;

// Central differences of the residual on each block's tangent space against
// the analytic columns.
void ExpectJacobianNear(const std::string& name, const TermOf& term_of,
                        double tolerance) {
  const ImuCurveState state = RandomState();
  const CurveTerm term = term_of(state);
  ASSERT_FALSE(term.blocks.empty()) << name;
  constexpr double kStep = 1e-6;
  for (size_t k = 0; k < term.blocks.size(); ++k) {
    for (int axis = 0; axis < 3; ++axis) {
      ImuCurveState plus = state, minus = state;
      plus.Plus(term.blocks[k], kStep * Eigen::Vector3d::Unit(axis));
      minus.Plus(term.blocks[k], -kStep * Eigen::Vector3d::Unit(axis));
      const Eigen::VectorXd numeric =
          (term_of(plus).r - term_of(minus).r) / (2.0 * kStep);
      const Eigen::VectorXd analytic = term.J.col(3 * k + axis);
      EXPECT_LT((numeric - analytic).norm(),
                tolerance * std::max(1.0, numeric.norm()))
          << name << ": block " << term.blocks[k] << " axis " << axis
          << "\nnumeric  " << numeric.transpose() << "\nanalytic "
          << analytic.transpose();
    }
  }
}

TEST(ImuCurveTerms, GyroIntervalJacobianMatchesNumericDiff) {
  const Eigen::Vector3d w(0.3, -1.2, 0.7);
  // Within one segment, and across two segments and a bias knot.
  for (const std::pair<double, double>& interval :
       {std::pair{0.112, 0.117}, std::pair{0.197, 0.2063}}) {
    const double t_a = interval.first, t_b = interval.second;
    ExpectJacobianNear(
        "gyroscope",
        [&](const ImuCurveState& s) {
          return GyroIntervalTerm(s, s.Spline(), t_a, t_b, w);
        },
        1e-6);
  }
}

TEST(ImuCurveTerms, AccelerometerJacobianMatchesNumericDiff) {
  const Eigen::Vector3d acc(0.4, 9.5, -1.1);
  for (const double t : {0.0, 0.123, 0.3499}) {
    ExpectJacobianNear(
        "accelerometer",
        [&](const ImuCurveState& s) {
          return AccelerometerTerm(s, s.Spline(), t, acc, 9.81);
        },
        1e-5);
  }
}

TEST(ImuCurveTerms, GroundTruthJacobiansMatchNumericDiff) {
  const Eigen::Vector3d p(0.1, 0.2, -0.3);
  const Eigen::Quaterniond q = ExpQuaternion(Eigen::Vector3d(0.5, -2.0, 1.0));
  ExpectJacobianNear(
      "position",
      [&](const ImuCurveState& s) {
        return PositionTerm(s, s.Spline(), 0.21, p);
      },
      1e-6);
  ExpectJacobianNear(
      "rotation",
      [&](const ImuCurveState& s) {
        return RotationTerm(s, s.Spline(), 0.21, q);
      },
      1e-6);
}

TEST(ImuCurveTerms, PriorJacobiansMatchNumericDiff) {
  ExpectJacobianNear(
      "position smoothness",
      [](const ImuCurveState& s) { return PositionSmoothnessTerm(s, 5); },
      1e-6);
  ExpectJacobianNear(
      "rotation smoothness",
      [](const ImuCurveState& s) { return RotationSmoothnessTerm(s, 5); },
      1e-6);
  for (const bool gyro : {true, false}) {
    ExpectJacobianNear(
        "bias walk",
        [&](const ImuCurveState& s) { return BiasWalkTerm(s, 1, gyro); }, 1e-6);
  }
}

TEST(ImuCurveTerms, BiasSplineInterpolatesItsKnots) {
  const ImuCurveState s = RandomState();
  EXPECT_TRUE(s.GyroBias(0.2).isApprox(s.b_g[1]));
  EXPECT_TRUE(s.AccelBias(0.3).isApprox(0.5 * (s.b_a[1] + s.b_a[2])));
  // Held beyond the last knot (0.6 s).
  EXPECT_TRUE(s.GyroBias(0.9).isApprox(s.b_g[3]));
}

}  // namespace
}  // namespace vio
