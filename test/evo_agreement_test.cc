// Our figures against values computed independently, the way evo defines
// them, on a small hand-made case: what `evo_ape tum GT EST --align` (se3),
// `--align --correct_scale` (sim3) and `evo_rpe ... --delta 1 --delta_unit f`
// would print. The references do not use eval/: the alignment is the least-
// squares optimum found by Ceres from several starts (Umeyama's closed form
// must agree with it), errors are taken with 4x4 matrices and trace formulas.

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "eval/alignment.h"
#include "eval/association.h"
#include "eval/metrics.h"
#include "test/testing/trajectories.h"

namespace vio {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr int64_t kMs = 1000000;  // [ns]

// Seven ground-truth poses (a bent, climbing loop) and an estimate made by
// hand: 3 ms late, in another frame (yaw 90 deg, shift, scale 0.9), with
// per-pose errors of a few cm and degrees, and one extra pose at 0.75 s that
// has no ground truth within 10 ms.
struct HandCase {
  Trajectory gt, est;
};

HandCase MakeHandCase() {
  const double gt_xyz_yaw[7][4] = {
      {0, 0, 0, 0},  {1, 0, 0.1, 10},    {2, 1, 0.2, 30},    {2, 2, 0.1, 60},
      {1, 3, 0, 90}, {0, 2.5, 0.3, 120}, {-0.5, 1, 0.2, 150}};
  const double err_xyz_rp[8][5] = {
      {0.02, -0.01, 0.03, 1, 0},  {-0.03, 0.02, 0.0, 0, 2},
      {0.05, 0.04, -0.02, -2, 1}, {0.0, -0.06, 0.01, 0, 0},
      {-0.04, 0.0, 0.05, 3, -1},  {0.01, 0.03, -0.04, 0, 0},
      {0.06, -0.02, 0.0, -1, 2},  {0, 0, 0, 0, 0}};
  const testing::Similarity S{testing::Yaw(90 * kDeg), {5, -1, 0.5}, 0.9};
  HandCase c;
  for (int i = 0; i < 8; ++i) {
    StampedPose g;
    g.t_ns = i * 100 * kMs;
    const double* row = gt_xyz_yaw[std::min(i, 6)];
    g.p_w_b = {row[0], row[1], row[2]};
    g.q_w_b = Eigen::Quaterniond(testing::Yaw(row[3] * kDeg));
    if (i < 7) c.gt.push_back(g);
    StampedPose e = S.Apply(g);
    e.t_ns = i < 7 ? g.t_ns + 3 * kMs : 750 * kMs;
    e.p_w_b +=
        Eigen::Vector3d(err_xyz_rp[i][0], err_xyz_rp[i][1], err_xyz_rp[i][2]);
    e.q_w_b =
        e.q_w_b *
        Eigen::AngleAxisd(err_xyz_rp[i][3] * kDeg, Eigen::Vector3d::UnitX()) *
        Eigen::AngleAxisd(err_xyz_rp[i][4] * kDeg, Eigen::Vector3d::UnitY());
    c.est.push_back(e);
  }
  return c;
}

// Residual p_gt - (exp(log_s) R(aa) p_est + t) of one associated pair.
struct PointResidual {
  Eigen::Vector3d p_est, p_gt;
  template <typename T>
  bool operator()(const T* aa, const T* t, const T* log_s, T* r) const {
    const T p[3] = {T(p_est.x()), T(p_est.y()), T(p_est.z())};
    T Rp[3];
    ceres::AngleAxisRotatePoint(aa, p, Rp);
    const T s = exp(log_s[0]);
    for (int k = 0; k < 3; ++k) r[k] = T(p_gt[k]) - (s * Rp[k] + t[k]);
    return true;
  }
};

struct Reference {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  double scale;
};

// The least-squares alignment by Ceres, best of several starting rotations.
Reference SolveAlignment(const Trajectory& est, const Trajectory& gt,
                         bool with_scale) {
  Reference best{};
  double best_cost = 1e300;
  for (double start_deg : {0.0, 90.0, 180.0, 270.0}) {
    double aa[3] = {0, 0, start_deg * kDeg}, t[3] = {0, 0, 0}, log_s = 0;
    ceres::Problem problem;
    for (size_t i = 0; i < est.size(); ++i) {
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<PointResidual, 3, 3, 3, 1>(
              new PointResidual{est[i].p_w_b, gt[i].p_w_b}),
          nullptr, aa, t, &log_s);
    }
    if (!with_scale) problem.SetParameterBlockConstant(&log_s);
    ceres::Solver::Options options;
    options.function_tolerance = 1e-16;
    options.gradient_tolerance = 1e-16;
    options.parameter_tolerance = 1e-16;
    options.max_num_iterations = 200;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    if (summary.final_cost < best_cost) {
      best_cost = summary.final_cost;
      double R[9];
      ceres::AngleAxisToRotationMatrix(aa, R);  // column-major
      best.R = Eigen::Map<Eigen::Matrix3d>(R);
      best.t = {t[0], t[1], t[2]};
      best.scale = std::exp(log_s);
    }
  }
  return best;
}

Eigen::Matrix4d Homogeneous(const Eigen::Matrix3d& R,
                            const Eigen::Vector3d& p) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = p;
  return T;
}

double TraceAngleDeg(const Eigen::Matrix3d& R) {
  return std::acos(std::clamp((R.trace() - 1.0) / 2.0, -1.0, 1.0)) / kDeg;
}

void CheckAgainstReference(AlignmentMode mode) {
  SCOPED_TRACE(AlignmentModeName(mode));
  const HandCase c = MakeHandCase();
  const Association assoc = Associate(c.est, c.gt, {0.01});
  ASSERT_EQ(assoc.size(), 7u);  // the 0.75 s estimate has no partner
  for (size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(assoc.ground_truth[i].t_ns, c.gt[i].t_ns);
  }
  const Alignment a = Align(assoc.estimate, assoc.ground_truth, mode);
  const Reference ref = SolveAlignment(assoc.estimate, assoc.ground_truth,
                                       mode == AlignmentMode::kSim3);
  EXPECT_LT((a.R_w_e - ref.R).norm(), 1e-7);
  EXPECT_LT((a.t_w_e - ref.t).norm(), 1e-7);
  EXPECT_NEAR(a.scale, ref.scale, 1e-8);

  // ATE, evo_ape's translation_part and angle_deg, from the reference.
  std::vector<double> e_m, e_deg;
  std::vector<Eigen::Matrix4d> P, Q;  // aligned estimate, ground truth
  for (size_t i = 0; i < 7; ++i) {
    const StampedPose& est = assoc.estimate[i];
    const StampedPose& gt = assoc.ground_truth[i];
    P.push_back(Homogeneous(ref.R * est.q_w_b.toRotationMatrix(),
                            ref.scale * ref.R * est.p_w_b + ref.t));
    Q.push_back(Homogeneous(gt.q_w_b.toRotationMatrix(), gt.p_w_b));
    const Eigen::Matrix4d E = P[i].inverse() * Q[i];
    const Eigen::Vector3d d =
        Q[i].topRightCorner<3, 1>() - P[i].topRightCorner<3, 1>();
    e_m.push_back(d.norm());
    e_deg.push_back(TraceAngleDeg(E.topLeftCorner<3, 3>()));
  }
  const AbsoluteTrajectoryError ate =
      ComputeAte(a.Apply(assoc.estimate), assoc.ground_truth);
  double sum = 0, sum_sq = 0;
  for (double e : e_m) {
    sum += e;
    sum_sq += e * e;
  }
  std::vector<double> sorted = e_m;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_NEAR(ate.translation.rmse, std::sqrt(sum_sq / 7), 1e-9);
  EXPECT_NEAR(ate.translation.mean, sum / 7, 1e-9);
  EXPECT_NEAR(ate.translation.median, sorted[3], 1e-9);
  EXPECT_NEAR(ate.translation.max, sorted[6], 1e-9);
  for (size_t i = 0; i < 7; ++i) {
    EXPECT_NEAR(ate.rotation_deg[i], e_deg[i], 1e-5);
  }
  EXPECT_GT(ate.translation.rmse, 0.01);  // a case with real errors

  // RPE, delta 1 frame: E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j).
  const RelativePoseError rpe = ComputeRpe(
      a.Apply(assoc.estimate), assoc.ground_truth, 1, RpeUnit::kFrames);
  ASSERT_EQ(rpe.pairs.size(), 6u);
  for (size_t i = 0; i + 1 < 7; ++i) {
    const Eigen::Matrix4d E =
        (Q[i].inverse() * Q[i + 1]).inverse() * (P[i].inverse() * P[i + 1]);
    const double t_m = E.topRightCorner<3, 1>().norm();
    const double angle_deg = TraceAngleDeg(E.topLeftCorner<3, 3>());
    EXPECT_NEAR(rpe.translation_m[i], t_m, 1e-9);
    EXPECT_NEAR(rpe.rotation_deg[i], angle_deg, 1e-5);
  }
}

TEST(EvoAgreement, Se3MatchesALeastSquaresReference) {
  CheckAgainstReference(AlignmentMode::kSe3);
}

TEST(EvoAgreement, Sim3MatchesALeastSquaresReference) {
  CheckAgainstReference(AlignmentMode::kSim3);
}

}  // namespace
}  // namespace vio
