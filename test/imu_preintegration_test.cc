#include "preintegration/imu_preintegration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <vector>

#include "geometry/so3.h"
#include "test/testing/analytic_trajectory.h"
#include "test/testing/jacobian_test_utils.h"

namespace vio {
namespace {

using testing::AnalyticTrajectory;
using testing::ExpectJacobianNear;

constexpr int64_t kPeriodNs = 5000000;  // 200 Hz
const Eigen::Vector3d kBa(0.12, -0.05, 0.2);
const Eigen::Vector3d kBg(0.01, -0.02, 0.005);

double Seconds(int64_t t_ns) { return 1e-9 * static_cast<double>(t_ns); }

// The true delta_p, delta_v, delta_q of [t0, t1] on the trajectory.
ImuDelta TrueDelta(const AnalyticTrajectory& traj, int64_t t0_ns,
                   int64_t t1_ns) {
  const double t0 = Seconds(t0_ns), t1 = Seconds(t1_ns), T = t1 - t0;
  const Eigen::Quaterniond q_i = traj.Rotation(t0);
  ImuDelta d;
  d.p = q_i.conjugate() * (traj.Position(t1) - traj.Position(t0) -
                           traj.Velocity(t0) * T - 0.5 * traj.g_w() * T * T);
  d.v = q_i.conjugate() *
        (traj.Velocity(t1) - traj.Velocity(t0) - traj.g_w() * T);
  d.q = q_i.conjugate() * traj.Rotation(t1);
  return d;
}

struct Errors {
  double p, theta, v;
};

Errors DeltaErrors(const ImuDelta& a, const ImuDelta& b) {
  return {(a.p - b.p).norm(), Log(a.q.conjugate() * b.q).norm(),
          (a.v - b.v).norm()};
}

// The leading discretisation error of the midpoint scheme with step h over
// [t0, t0 + T] (global error of the trapezoid rule, T h^2 / 12 max|f''|):
//   theta: T h^2/12 (max|w''| + max|w| max|w'|)  (trapezoid on w, plus the
//          commutator of rotations within a step)
//   v:     T h^2/12 max|p''''| + T e_theta max|p'' - g|
//   p:     h^2/12 |p''(t1) - p''(t0)|  (the step's a h^2 / 2 instead of
//          the exact double integral: h^3/12 f' per step, summing to
//          h^2/12 (f(t1) - f(t0)) with f = R_i^T (p'' - g))
//          + T^2 h^2/24 max|p''''| + T^2 e_theta max|p'' - g| / 2
// Maxima are taken on a 1 ms grid (w's derivatives by central differences).
// The test allows twice these, for the interpolated ends and higher orders.
Errors DiscretisationBound(const AnalyticTrajectory& traj, double t0, double T,
                           double h) {
  double w = 0, dw = 0, ddw = 0, p4 = 0, acc = 0;
  const double e = 1e-3;
  for (double t = t0; t <= t0 + T; t += 1e-3) {
    w = std::max(w, traj.AngularVelocity(t).norm());
    dw = std::max(
        dw,
        ((traj.AngularVelocity(t + e) - traj.AngularVelocity(t - e)) / (2 * e))
            .norm());
    ddw = std::max(ddw,
                   ((traj.AngularVelocity(t + e) - 2 * traj.AngularVelocity(t) +
                     traj.AngularVelocity(t - e)) /
                    (e * e))
                       .norm());
    p4 = std::max(p4, traj.PositionDerivative(t, 4).norm());
    acc = std::max(acc, (traj.PositionDerivative(t, 2) - traj.g_w()).norm());
  }
  const double h2 = h * h;
  Errors b;
  b.theta = T * h2 / 12 * (ddw + w * dw);
  b.v = T * h2 / 12 * p4 + T * b.theta * acc;
  const double df =
      (traj.PositionDerivative(t0 + T, 2) - traj.PositionDerivative(t0, 2))
          .norm();
  b.p = h2 / 12 * df + T * T * h2 / 24 * p4 + T * T * b.theta * acc / 2;
  return b;
}

TEST(ImuPreintegration, NoiseFreeSamplesMatchTrueRelativeMotion) {
  const AnalyticTrajectory traj;
  // Interval ends between samples, so both ends are interpolated.
  const int64_t t0_ns = 1000000000 + 1700000, t1_ns = t0_ns + 500000000;
  const std::vector<ImuSample> samples =
      traj.Samples(900000000, 1600000000, kPeriodNs, kBa, kBg);
  const ImuPreintegration pre(t0_ns, t1_ns, samples, kBa, kBg, ImuNoise(),
                              PreintegrationOptions());
  EXPECT_DOUBLE_EQ(pre.sum_dt(), 0.5);
  const Errors err = DeltaErrors(pre.delta(), TrueDelta(traj, t0_ns, t1_ns));
  const Errors bound =
      DiscretisationBound(traj, Seconds(t0_ns), 0.5, Seconds(kPeriodNs));
  EXPECT_LE(err.p, 2 * bound.p);
  EXPECT_LE(err.theta, 2 * bound.theta);
  EXPECT_LE(err.v, 2 * bound.v);
}

TEST(ImuPreintegration, DiscretisationErrorShrinksWithTheSquareOfTheStep) {
  const AnalyticTrajectory traj;
  const int64_t t0_ns = 1000000000, t1_ns = t0_ns + 500000000;
  std::vector<Errors> errors;
  for (int64_t period_ns : {kPeriodNs, kPeriodNs / 2, kPeriodNs / 4}) {
    const ImuPreintegration pre(t0_ns, t1_ns,
                                traj.Samples(t0_ns, t1_ns, period_ns, kBa, kBg),
                                kBa, kBg, ImuNoise(), PreintegrationOptions());
    errors.push_back(DeltaErrors(pre.delta(), TrueDelta(traj, t0_ns, t1_ns)));
  }
  for (size_t i = 0; i + 1 < errors.size(); ++i) {
    // Halving h divides an O(h^2) error by 4.
    EXPECT_NEAR(errors[i].p / errors[i + 1].p, 4.0, 0.5);
    EXPECT_NEAR(errors[i].theta / errors[i + 1].theta, 4.0, 0.5);
    EXPECT_NEAR(errors[i].v / errors[i + 1].v, 4.0, 0.5);
  }
}

// [dp, dtheta, dv] of `d` relative to `ref` (9).
Eigen::Matrix<double, 9, 1> DeltaDifference(const ImuDelta& d,
                                            const ImuDelta& ref) {
  Eigen::Matrix<double, 9, 1> out;
  out << d.p - ref.p, Log(ref.q.conjugate() * d.q), d.v - ref.v;
  return out;
}

class ImuPreintegrationOnTrajectory : public ::testing::Test {
 protected:
  ImuPreintegration Integrate(int64_t t0_ns, int64_t t1_ns,
                              const Eigen::Vector3d& b_a,
                              const Eigen::Vector3d& b_g) const {
    return ImuPreintegration(t0_ns, t1_ns, samples_, b_a, b_g, ImuNoise(),
                             PreintegrationOptions());
  }

  const AnalyticTrajectory traj_;
  const std::vector<ImuSample> samples_ =
      traj_.Samples(0, 2000000000, kPeriodNs, kBa, kBg);
  const int64_t t0_ns_ = 300000000 + 1234567;
  const int64_t t1_ns_ = t0_ns_ + 450000000;
};

TEST_F(ImuPreintegrationOnTrajectory, BiasJacobiansMatchReintegration) {
  const ImuPreintegration pre = Integrate(t0_ns_, t1_ns_, kBa, kBg);
  const PreintegratedImu& r = pre.result();
  Eigen::Matrix<double, 9, 6> J = Eigen::Matrix<double, 9, 6>::Zero();
  J.block<3, 3>(0, 0) = r.d_dp_d_ba;
  J.block<3, 3>(0, 3) = r.d_dp_d_bg;
  J.block<3, 3>(3, 3) = r.d_dq_d_bg;
  J.block<3, 3>(6, 0) = r.d_dv_d_ba;
  J.block<3, 3>(6, 3) = r.d_dv_d_bg;
  const auto reintegrated = [&](const Eigen::VectorXd& db) -> Eigen::VectorXd {
    const ImuPreintegration p =
        Integrate(t0_ns_, t1_ns_, kBa + db.head<3>(), kBg + db.tail<3>());
    return DeltaDifference(p.delta(), pre.delta());
  };
  ExpectJacobianNear("d [dp, dq, dv] / d [b_a, b_g]", J, reintegrated,
                     Eigen::VectorXd::Zero(6), 1e-6, 1e-5);
}

TEST_F(ImuPreintegrationOnTrajectory,
       CorrectionErrorIsSecondOrderInBiasChange) {
  // The first-order correction leaves an error quadratic in the bias change:
  // halving the change divides it by about 4, and it is a small fraction of
  // the change it corrects.
  const ImuPreintegration pre = Integrate(t0_ns_, t1_ns_, kBa, kBg);
  const Eigen::Vector3d step_a(0.08, -0.05, 0.06), step_g(0.006, 0.004, -0.008);
  double previous = 0.0;
  for (double scale : {1.0, 0.5, 0.25}) {
    const Eigen::Vector3d b_a = kBa + scale * step_a,
                          b_g = kBg + scale * step_g;
    const ImuDelta exact = Integrate(t0_ns_, t1_ns_, b_a, b_g).delta();
    const double change = DeltaDifference(pre.delta(), exact).norm();
    const double residual =
        DeltaDifference(pre.Corrected(b_a, b_g), exact).norm();
    EXPECT_LT(residual, 0.01 * change) << "scale " << scale;
    if (previous > 0.0) {
      EXPECT_NEAR(previous / residual, 4.0, 0.4);
    }
    previous = residual;
  }
}

TEST_F(ImuPreintegrationOnTrajectory, RepropagatesOnlyBeyondTheThresholds) {
  ImuPreintegration pre = Integrate(t0_ns_, t1_ns_, kBa, kBg);
  const PreintegrationOptions options;
  const Eigen::Vector3d small_a(0.9 * options.repropagate_acc_bias_change, 0,
                                0);
  EXPECT_FALSE(pre.UpdateBiasEstimate(kBa + small_a, kBg));
  EXPECT_EQ(pre.lin_b_a(), kBa);

  const Eigen::Vector3d big_g(0, 0, 1.1 * options.repropagate_gyr_bias_change);
  EXPECT_TRUE(pre.NeedsRepropagation(kBa, kBg + big_g));
  EXPECT_TRUE(pre.UpdateBiasEstimate(kBa + small_a, kBg + big_g));
  EXPECT_EQ(pre.lin_b_a(), kBa + small_a);
  EXPECT_EQ(pre.lin_b_g(), kBg + big_g);
  const ImuPreintegration fresh =
      Integrate(t0_ns_, t1_ns_, kBa + small_a, kBg + big_g);
  EXPECT_EQ(DeltaDifference(pre.delta(), fresh.delta()).norm(), 0.0);
  EXPECT_EQ(pre.covariance(), fresh.covariance());
}

TEST_F(ImuPreintegrationOnTrajectory, MergeAtASampleEqualsTheJointInterval) {
  const int64_t t_mid_ns = 500000000;  // a sample stamp
  const ImuPreintegration merged = ImuPreintegration::Merge(
      Integrate(t0_ns_, t_mid_ns, kBa, kBg),
      Integrate(t_mid_ns, t1_ns_, kBa + Eigen::Vector3d::Constant(0.1), kBg));
  const ImuPreintegration joint = Integrate(t0_ns_, t1_ns_, kBa, kBg);
  EXPECT_EQ(merged.t0_ns(), t0_ns_);
  EXPECT_EQ(merged.t1_ns(), t1_ns_);
  EXPECT_EQ(merged.samples().size(), joint.samples().size());
  EXPECT_LT(DeltaDifference(merged.delta(), joint.delta()).norm(), 1e-14);
  EXPECT_TRUE(merged.covariance().isApprox(joint.covariance(), 1e-12));
  EXPECT_TRUE(
      merged.result().d_dp_d_bg.isApprox(joint.result().d_dp_d_bg, 1e-12));
}

// Merge continues the first interval's integration instead of starting again
// from t0: a chain of merges (a keyframe interval absorbing frame after frame,
// boundaries on and between samples, the later intervals linearised at other
// biases) must equal, bit for bit, integrating the joined samples from the
// start with the first interval's biases (Repropagate at the same biases).
TEST_F(ImuPreintegrationOnTrajectory, MergeEqualsIntegratingFromTheStart) {
  const int64_t cuts[] = {t0_ns_,    400000000, 447500000,
                          500000000, 641250000, t1_ns_};
  ImuPreintegration merged = Integrate(cuts[0], cuts[1], kBa, kBg);
  for (size_t k = 1; k + 1 < std::size(cuts); ++k) {
    merged = ImuPreintegration::Merge(
        merged, Integrate(cuts[k], cuts[k + 1],
                          kBa + Eigen::Vector3d::Constant(0.05 * k), kBg));
  }
  ImuPreintegration fresh = merged;
  fresh.Repropagate(merged.lin_b_a(), merged.lin_b_g());
  EXPECT_EQ(merged.t0_ns(), t0_ns_);
  EXPECT_EQ(merged.t1_ns(), t1_ns_);
  EXPECT_EQ(merged.lin_b_a(), kBa);
  EXPECT_EQ(merged.delta().p, fresh.delta().p);
  EXPECT_EQ(merged.delta().v, fresh.delta().v);
  EXPECT_EQ(merged.delta().q.coeffs(), fresh.delta().q.coeffs());
  EXPECT_EQ(merged.covariance(), fresh.covariance());
  EXPECT_EQ(merged.result().d_dp_d_ba, fresh.result().d_dp_d_ba);
  EXPECT_EQ(merged.result().d_dp_d_bg, fresh.result().d_dp_d_bg);
  EXPECT_EQ(merged.result().d_dq_d_bg, fresh.result().d_dq_d_bg);
  EXPECT_EQ(merged.result().d_dv_d_ba, fresh.result().d_dv_d_ba);
  EXPECT_EQ(merged.result().d_dv_d_bg, fresh.result().d_dv_d_bg);
  // And a merged interval re-linearised later is a plain interval again.
  merged.Repropagate(kBa + Eigen::Vector3d::Constant(0.2), kBg);
  fresh.Repropagate(kBa + Eigen::Vector3d::Constant(0.2), kBg);
  EXPECT_EQ(merged.covariance(), fresh.covariance());
  EXPECT_EQ(merged.delta().p, fresh.delta().p);
}

TEST_F(ImuPreintegrationOnTrajectory,
       MergeBetweenSamplesStaysWithinDiscretisation) {
  const int64_t t_mid_ns = 500000000 + 2500000;  // halfway between samples
  const ImuPreintegration merged =
      ImuPreintegration::Merge(Integrate(t0_ns_, t_mid_ns, kBa, kBg),
                               Integrate(t_mid_ns, t1_ns_, kBa, kBg));
  const ImuPreintegration joint = Integrate(t0_ns_, t1_ns_, kBa, kBg);
  EXPECT_EQ(merged.samples().size(), joint.samples().size() + 1);
  // The extra sample at t_mid changes one step: a local error O(h^3).
  EXPECT_LT(DeltaDifference(merged.delta(), joint.delta()).norm(), 1e-6);
}

TEST_F(ImuPreintegrationOnTrajectory, ShortIntervalWithinOneSampleStep) {
  // 1 ms inside one 5 ms step: both ends interpolated, a single step. Its
  // error is dominated by the linear interpolation of the samples,
  // h^2/8 max|s''| for a signal s and sample step h, over tau = 1 ms;
  // allowed twice that, with s'' by central differences.
  const int64_t t0_ns = 700000000 + 1000000, t1_ns = t0_ns + 1000000;
  const ImuPreintegration pre = Integrate(t0_ns, t1_ns, kBa, kBg);
  ASSERT_EQ(pre.samples().size(), 2u);
  const int64_t e_ns = 1000000;
  const auto second = [&](int64_t t) {
    const ImuSample a = traj_.Sample(t - e_ns, kBa, kBg);
    const ImuSample b = traj_.Sample(t, kBa, kBg);
    const ImuSample c = traj_.Sample(t + e_ns, kBa, kBg);
    const double e2 = Seconds(e_ns) * Seconds(e_ns);
    return std::make_pair((a.acc - 2 * b.acc + c.acc).norm() / e2,
                          (a.gyr - 2 * b.gyr + c.gyr).norm() / e2);
  };
  double acc2 = 0, gyr2 = 0;
  for (int64_t t = 700000000; t <= 705000000; t += 1000000) {
    acc2 = std::max(acc2, second(t).first);
    gyr2 = std::max(gyr2, second(t).second);
  }
  const double h = Seconds(kPeriodNs), tau = 1e-3;
  const Errors err = DeltaErrors(pre.delta(), TrueDelta(traj_, t0_ns, t1_ns));
  EXPECT_LT(err.v, 2 * tau * h * h / 8 * acc2);
  EXPECT_LT(err.theta, 2 * tau * h * h / 8 * gyr2);
  EXPECT_TRUE(pre.covariance().allFinite());
  EXPECT_GT(pre.covariance().diagonal().minCoeff(), 0.0);
}

}  // namespace
}  // namespace vio
