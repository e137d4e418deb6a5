#include "geometry/pose_spline.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "geometry/so3.h"
#include "testing/jacobian_test_utils.h"

namespace vio {
namespace {

// A spline with control points scattered around a wavy path, so every
// segment bends and turns.
PoseSpline RandomSpline(int n, double dt, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Vector3d> p(n);
  std::vector<Eigen::Quaterniond> q(n);
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  for (int k = 0; k < n; ++k) {
    p[k] = Eigen::Vector3d(std::sin(0.3 * k), 0.1 * k, 0.5) +
           0.2 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    q[k] = rotation;
    rotation =
        rotation * ExpQuaternion(0.3 * Eigen::Vector3d(normal(rng), normal(rng),
                                                       normal(rng)));
  }
  return PoseSpline(1.5, dt, p, q);
}

TEST(PoseSpline, AnalyticDerivativesMatchCentralDifferences) {
  const PoseSpline spline = RandomSpline(12, 0.1, 3);
  constexpr double h = 1e-5;
  for (double t = spline.start_s() + 0.013; t < spline.end_s() - h;
       t += 0.037) {
    SCOPED_TRACE(t);
    const PoseSplineState x = spline.Evaluate(t);
    const PoseSplineState before = spline.Evaluate(t - h);
    const PoseSplineState after = spline.Evaluate(t + h);
    EXPECT_LT((x.v - (after.p - before.p) / (2 * h)).norm(), 1e-6);
    EXPECT_LT((x.a - (after.v - before.v) / (2 * h)).norm(), 1e-5);
    // R(t + h) = R(t - h) Exp(2 h w) to second order.
    const Eigen::Vector3d w = Log(before.q.conjugate() * after.q) / (2 * h);
    EXPECT_LT((x.w - w).norm(), 1e-6);
    EXPECT_LT((x.dw - (after.w - before.w) / (2 * h)).norm(), 1e-4);
  }
}

TEST(PoseSpline, ReproducesACubicPolynomialExactly) {
  // Control points sampled from a cubic at their "seats" (point k sits at
  // t0 + (k - 1) dt) are not the curve's values, but the B-spline of a
  // polynomial of degree <= 3 is that polynomial when the control points are
  // c_k = P(t_k) - dt^2/6 P''(t_k) (the classic quasi-interpolant).
  const double dt = 0.2, t0 = -0.4;
  auto P = [](double t) {
    return Eigen::Vector3d(1 + 2 * t - t * t + 0.5 * t * t * t, 3 * t, -t * t);
  };
  auto P2 = [](double t) { return Eigen::Vector3d(-2 + 3 * t, 0.0, -2.0); };
  std::vector<Eigen::Vector3d> c;
  for (int k = 0; k < 10; ++k) {
    const double tk = t0 + (k - 1) * dt;
    c.push_back(P(tk) - dt * dt / 6.0 * P2(tk));
  }
  const PoseSpline spline(
      t0, dt, c,
      std::vector<Eigen::Quaterniond>(10, Eigen::Quaterniond::Identity()));
  for (double t = spline.start_s(); t <= spline.end_s(); t += 0.01) {
    const PoseSplineState x = spline.Evaluate(t);
    EXPECT_LT((x.p - P(t)).norm(), 1e-12) << t;
    EXPECT_LT((x.a - P2(t)).norm(), 1e-9) << t;
    EXPECT_LT(x.w.norm(), 1e-15);
  }
}

TEST(PoseSpline, ConstantRateRotationHasThatRate) {
  // Control rotations Exp(k dt w) with a fixed axis give increments
  // d = dt w, and the cumulative basis sums to a linear function of t with
  // slope 1/dt: the curve is Exp((t - t0 + dt) w) up to a constant offset.
  const Eigen::Vector3d w(0.3, -0.2, 0.9);
  const double dt = 0.1;
  std::vector<Eigen::Quaterniond> q;
  for (int k = 0; k < 8; ++k) q.push_back(ExpQuaternion(k * dt * w));
  const PoseSpline spline(0.0, dt, std::vector<Eigen::Vector3d>(8), q);
  for (double t = 0.0; t <= spline.end_s(); t += 0.03) {
    const PoseSplineState x = spline.Evaluate(t);
    EXPECT_LT((x.w - w).norm(), 1e-12) << t;
    EXPECT_LT(x.dw.norm(), 1e-12) << t;
    EXPECT_LT(Log(x.q.conjugate() * ExpQuaternion((t + dt) * w)).norm(), 1e-12)
        << t;
  }
}

TEST(PoseSpline, RotationJacobianMatchesNumericDiff) {
  const PoseSpline spline = RandomSpline(9, 0.25, 7);
  for (double t : {spline.start_s() + 0.05, spline.start_s() + 0.31,
                   spline.start_s() + 0.77, spline.end_s() - 0.05}) {
    std::array<Eigen::Matrix3d, PoseSpline::kOrder> J;
    int first = 0;
    const Eigen::Quaterniond q0 = spline.Rotation(t, &J, &first);
    for (int k = 0; k < PoseSpline::kOrder; ++k) {
      auto f = [&](const Eigen::VectorXd& e) {
        std::vector<Eigen::Quaterniond> q = spline.rotations();
        q[first + k] = q[first + k] * ExpQuaternion(e);
        const PoseSpline moved(spline.start_s(), spline.dt_s(),
                               spline.positions(), q);
        return Eigen::VectorXd(
            Log(q0.conjugate() * moved.Rotation(t, nullptr, nullptr)));
      };
      testing::ExpectJacobianNear("d_R_d_ctrl" + std::to_string(k), J[k], f,
                                  Eigen::VectorXd::Zero(3), 1e-6);
    }
  }
}

TEST(PoseSpline, RejectsBadInput) {
  std::vector<Eigen::Vector3d> p(3);
  std::vector<Eigen::Quaterniond> q(3);
  EXPECT_THROW(PoseSpline(0.0, 0.1, p, q), std::invalid_argument);
  p.resize(4);
  q.resize(4, Eigen::Quaterniond::Identity());
  EXPECT_THROW(PoseSpline(0.0, 0.0, p, q), std::invalid_argument);
  const PoseSpline spline(0.0, 0.1, p, q);
  EXPECT_NO_THROW(spline.Evaluate(0.1));
  EXPECT_THROW(spline.Evaluate(0.1 + 1e-6), std::out_of_range);
  EXPECT_THROW(spline.Evaluate(-1e-6), std::out_of_range);
}

}  // namespace
}  // namespace vio
