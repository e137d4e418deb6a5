// The window's correction (estimator/window_rescale.h) and the spread ratio the
// realignment measures it by (estimator/scale_realignment.h): checked
// against the geometry they must produce, computed independently here.

#include "estimator/window_rescale.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "estimator/scale_realignment.h"

namespace vio {
namespace {

// A window of n frames on a curve, camera 0 at the body origin (so that a
// point's depth in its anchor scales exactly with the positions).
Window MakeWindow(int n) {
  Window w;
  w.extrinsics[0] = {0, 0, 0, 0, 0, 0, 1};
  for (int k = 0; k < n; ++k) {
    auto f = std::make_unique<WindowFrame>();
    f->id = k;
    f->t_ns = f->t_imu_ns = 1000000000LL + 100000000LL * k;
    const double a = 0.3 * k;
    f->p_w_b() = Eigen::Vector3d(2.0 * std::cos(a), 1.5 * std::sin(a), 0.2 * k);
    f->q_w_b() = Eigen::Quaterniond(Eigen::AngleAxisd(
        0.1 * k, Eigen::Vector3d(0.2, 0.3, 1.0).normalized()));
    f->v_w() = Eigen::Vector3d(-0.6 * std::sin(a), 0.45 * std::cos(a), 0.2);
    f->b_a() = Eigen::Vector3d(0.01, -0.02, 0.03);
    f->b_g() = Eigen::Vector3d(0.001, 0.002, -0.003);
    w.frames.push_back(std::move(f));
  }
  return w;
}

// The world position of an inverse-depth landmark, from its anchor.
Eigen::Vector3d PointOf(const Landmark& l, const Window& w) {
  const Sighting& a = l.anchor();
  const Eigen::Vector3d p_c =
      Eigen::Vector3d(a.xy.x(), a.xy.y(), 1.0) / l.inverse_depth;
  return w.T_w_c(a.frame_id, a.camera) * p_c;
}

// Landmarks seen from every frame: points 0..m-1 as inverse depths, the
// last one made a world point.
FeatureManager MakeFeatures(const Window& w, int m) {
  FeatureManager features(1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < m; ++i) {
    points.emplace_back(4.0 + 0.3 * i, -1.0 + 0.25 * i, 3.0 - 0.1 * i);
  }
  for (const auto& f : w.frames) {
    std::vector<FeatureObservation> obs;
    for (int i = 0; i < m; ++i) {
      const Eigen::Vector3d p_c = w.T_w_c(f->id, 0).inverse() * points[i];
      FeatureObservation o;
      o.feature_id = i;
      o.xy = p_c.head<2>() / p_c.z();
      obs.push_back(o);
    }
    features.AddFrame(f->id, obs);
  }
  for (auto& [id, l] : features.landmarks()) {
    const Eigen::Vector3d p_c =
        w.T_w_c(l.anchor().frame_id, 0).inverse() * points[id];
    l.triangulated = true;
    l.inverse_depth = 1.0 / p_c.z();
  }
  Landmark& last = features.landmarks().at(m - 1);
  last.triangulated = false;
  last.world_point = true;
  for (int j = 0; j < 3; ++j) {
    last.p_w[j] = points[m - 1][j];
    last.p_w_first[j] = points[m - 1][j] + 0.01;
  }
  return features;
}

WindowCorrection Correction(const Window& w) {
  WindowCorrection k;
  k.s = 1.23;
  k.R = Eigen::AngleAxisd(0.02, Eigen::Vector3d(1.0, -0.5, 0.2).normalized())
            .toRotationMatrix();
  k.c = w.frames.back()->p_w_b_value();
  k.delta_b_a = Eigen::Vector3d(0.03, -0.01, 0.02);
  return k;
}

TEST(CorrectWindow, MapsPositionsVelocitiesAttitudesAndPointsBySimilarity) {
  Window w = MakeWindow(4);
  FeatureManager features = MakeFeatures(w, 5);
  const Window before = MakeWindow(4);
  std::vector<Eigen::Vector3d> points_before;
  for (const auto& [id, l] : features.landmarks()) {
    points_before.push_back(l.world_point ? Eigen::Vector3d(l.p_w.data())
                                          : PointOf(l, w));
  }
  const Eigen::Vector3d p_w_first_before(
      features.landmarks().at(4).p_w_first.data());
  const WindowCorrection k = Correction(w);
  const double s = k.s;
  const Eigen::Vector3d c = k.c;
  auto map = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    return c + s * (k.R * (p - c));
  };
  CorrectWindow(k, &w, &features);
  for (size_t i = 0; i < w.frames.size(); ++i) {
    const WindowFrame& a = *before.frames[i];
    const WindowFrame& b = *w.frames[i];
    EXPECT_LT((b.p_w_b_value() - map(a.p_w_b_value())).norm(), 1e-12);
    EXPECT_LT((b.v_w_value() - s * (k.R * a.v_w_value())).norm(), 1e-12);
    const Eigen::Matrix3d R_a = a.T_w_b().linear(), R_b = b.T_w_b().linear();
    EXPECT_LT((R_b - k.R * R_a).norm(), 1e-12);
    EXPECT_LT((Eigen::Vector3d(b.speed_bias.data() + kSbBa) -
               Eigen::Vector3d(a.speed_bias.data() + kSbBa) - k.delta_b_a)
                  .norm(),
              1e-15);
    EXPECT_EQ(b.b_g_value(), a.b_g_value());
  }
  // The newest frame, the centre, does not move.
  EXPECT_LT((w.frames.back()->p_w_b_value() - c).norm(), 1e-12);
  size_t i = 0;
  for (const auto& [id, l] : features.landmarks()) {
    const Eigen::Vector3d p =
        l.world_point ? Eigen::Vector3d(l.p_w.data()) : PointOf(l, w);
    EXPECT_LT((p - map(points_before[i])).norm(), 1e-9) << id;
    ++i;
  }
  EXPECT_LT((Eigen::Vector3d(features.landmarks().at(4).p_w_first.data()) -
             map(p_w_first_before))
                .norm(),
            1e-12);
}

// Evaluates a prior at the given blocks.
Eigen::VectorXd Residual(const MarginalizationPrior& prior,
                         const std::vector<double*>& blocks) {
  Eigen::VectorXd r(prior.num_residuals());
  std::vector<const double*> p(blocks.begin(), blocks.end());
  EXPECT_TRUE(prior.Evaluate(p.data(), r.data(), nullptr));
  return r;
}

TEST(CorrectPrior, SaysOfTheCorrectedStateWhatItSaidOfTheOriginal) {
  Window w = MakeWindow(3);
  FeatureManager features = MakeFeatures(w, 3);
  double* point = features.landmarks().at(2).p_w.data();
  double extrinsic[7] = {0.1, 0.0, -0.05, 0, 0, 0, 1};
  const std::vector<double*> blocks = {
      w.frames[0]->pose.data(), w.frames[0]->speed_bias.data(),
      w.frames[1]->pose.data(), point, extrinsic};
  // A prior with a random square root and offset, linearised at the
  // current values.
  std::vector<PriorBlock> kinds = {{PriorBlockKind::kPose, {}},
                                   {PriorBlockKind::kEuclidean, {}},
                                   {PriorBlockKind::kPose, {}},
                                   {PriorBlockKind::kEuclidean, {}},
                                   {PriorBlockKind::kPose, {}}};
  const int sizes[] = {7, 9, 7, 3, 7};
  for (size_t b = 0; b < kinds.size(); ++b) {
    kinds[b].x0.assign(blocks[b], blocks[b] + sizes[b]);
  }
  const int n = 6 + 9 + 6 + 3 + 6;
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd J(n, n);
  Eigen::VectorXd r0(n);
  for (int i = 0; i < n; ++i) {
    r0(i) = g(rng);
    for (int j = 0; j < n; ++j) J(i, j) = g(rng);
  }
  const MarginalizationPrior prior(kinds, J, r0);
  // Move the state away from x0 (positions, velocities, attitudes, the
  // point, the extrinsic), then rescale it and the prior.
  for (double* b : {blocks[0], blocks[2]}) {
    b[0] += 0.05;
    b[1] -= 0.02;
    Eigen::Map<Eigen::Quaterniond> q(b + 3);
    q = (q *
         Eigen::Quaterniond(Eigen::AngleAxisd(0.03, Eigen::Vector3d::UnitY())))
            .normalized();
  }
  blocks[1][0] += 0.1;
  blocks[1][4] += 0.01;
  point[2] += 0.07;
  extrinsic[1] += 0.01;
  const Eigen::VectorXd r_original = Residual(prior, blocks);
  WindowCorrection k = Correction(w);
  k.s = 0.83;
  const std::unique_ptr<MarginalizationPrior> rescaled =
      CorrectPrior(prior, blocks, k, w, features);
  CorrectWindow(k, &w, &features);
  const Eigen::VectorXd r_rescaled = Residual(*rescaled, blocks);
  EXPECT_LT((r_rescaled - r_original).norm(), 1e-9 * r_original.norm());
  // The old prior at the rescaled state says something else (the check
  // above can fail).
  EXPECT_GT((Residual(prior, blocks) - r_original).norm(), 0.1);
  // Its linearisation point moved with the state: at the rescaled x0 the
  // residual is r0.
  for (size_t b = 0; b < blocks.size(); ++b) {
    const std::vector<double>& x0 = rescaled->blocks()[b].x0;
    std::copy(x0.begin(), x0.end(), blocks[b]);
  }
  EXPECT_LT((Residual(*rescaled, blocks) - r0).norm(), 1e-9 * r0.norm());
  // The extrinsic (neither a frame nor a point) kept its x0.
  EXPECT_EQ(rescaled->blocks()[4].x0, kinds[4].x0);
}

TEST(SpreadRatio, IsTheScaleBetweenTwoTrajectoriesWhateverTheirGauge) {
  const Window w = MakeWindow(6);
  // Reference frames halfway between window frames (where the window's
  // positions are interpolated: on its straight segments), in another
  // gauge and 1.3 times the window's scale; one before the window, ignored.
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d t(5.0, -2.0, 1.0);
  std::vector<InitialFrame> reference;
  InitialFrame early;
  early.t_imu_ns = w.frames.front()->t_imu_ns - 50000000;
  early.p_w_b = Eigen::Vector3d(100, 100, 100);
  reference.push_back(early);
  for (size_t k = 0; k + 1 < w.frames.size(); ++k) {
    const WindowFrame& a = *w.frames[k];
    const WindowFrame& b = *w.frames[k + 1];
    InitialFrame f;
    f.t_imu_ns = (a.t_imu_ns + b.t_imu_ns) / 2;
    f.p_w_b = R * (1.3 * 0.5 * (a.p_w_b_value() + b.p_w_b_value())) + t;
    reference.push_back(f);
  }
  int common = 0;
  EXPECT_NEAR(SpreadRatio(reference, w, 4, &common), 1.3, 1e-12);
  EXPECT_EQ(common, 5);
  // Too few frames in common: no ratio.
  EXPECT_EQ(SpreadRatio(reference, w, 6, &common), 0.0);
}

}  // namespace
}  // namespace vio
