#include "estimator/visual_tracker.h"

#include <gtest/gtest.h>

#include <random>

#include "geometry/so3.h"

namespace vio {
namespace {

// A window of two frames (body poses 0.3 m apart, the EuRoC cam0 extrinsic
// and a cam1 0.11 m to its right) and 60 landmarks 3-9 m ahead,
// triangulated from noise-free observations.
class Scene {
 public:
  explicit Scene(int cameras) : features_(cameras) {
    window_.num_cameras = cameras;
    Eigen::Isometry3d T_b_c = Eigen::Isometry3d::Identity();
    T_b_c.linear() << 0, -1, 0, 1, 0, 0, 0, 0, 1;  // camera z = body z
    T_b_c.translation() = Eigen::Vector3d(-0.02, -0.06, 0.01);
    window_.extrinsics[0] = PoseArray(T_b_c);
    T_b_c.translation() += T_b_c.linear() * Eigen::Vector3d(0.11, 0, 0);
    window_.extrinsics[1] = PoseArray(T_b_c);
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 60; ++i) {
      const double z = 6.0 + 3.0 * u(rng);
      points_w_.push_back({0.5 * z * u(rng), 0.4 * z * u(rng), z});
    }
    for (int k = 0; k < 2; ++k) {
      auto f = std::make_unique<WindowFrame>();
      f->id = k;
      f->pose = PoseArray(BodyPose(k));
      features_.AddFrame(k, Observe(BodyPose(k)));
      window_.frames.push_back(std::move(f));
    }
    TriangulationOptions t;
    features_.TriangulateNew(
        [this](int64_t id, int c) { return window_.T_w_c(id, c); }, t);
  }

  // Frame k at x = 0.3 k, yawing 2 deg per frame.
  static Eigen::Isometry3d BodyPose(double k) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Exp(Eigen::Vector3d(0.01 * k, -0.02 * k, 0.035 * k));
    T.translation() = Eigen::Vector3d(0.3 * k, 0.05 * k, -0.02 * k);
    return T;
  }

  std::vector<FeatureObservation> Observe(
      const Eigen::Isometry3d& T_w_b) const {
    std::vector<FeatureObservation> out;
    for (int c = 0; c < window_.num_cameras; ++c) {
      const Eigen::Isometry3d T_c_w = (T_w_b * window_.T_b_c(c)).inverse();
      for (size_t i = 0; i < points_w_.size(); ++i) {
        const Eigen::Vector3d p_c = T_c_w * points_w_[i];
        FeatureObservation o;
        o.feature_id = static_cast<int64_t>(i);
        o.camera = c;
        o.xy = p_c.head<2>() / p_c.z();
        out.push_back(o);
      }
    }
    return out;
  }

  Window window_;
  FeatureManager features_;
  std::vector<Eigen::Vector3d> points_w_;
};

double PoseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm() +
         Log(Eigen::Matrix3d(a.linear().transpose() * b.linear())).norm();
}

TEST(TrackPoseOnLandmarks, RecoversTheTruePoseFromADistantGuess) {
  const Scene scene(1);
  const Eigen::Isometry3d truth = Scene::BodyPose(2.0);
  // The guess: the newest window frame, 0.3 m and 2 deg away.
  const VisualPose pose =
      TrackPoseOnLandmarks(scene.window_, scene.features_, scene.Observe(truth),
                           Scene::BodyPose(1.0), VisualTrackerSettings());
  ASSERT_TRUE(pose.ok);
  EXPECT_EQ(pose.landmarks, 60);
  EXPECT_EQ(pose.inliers, 60);
  EXPECT_LT(PoseError(pose.T_w_b, truth), 1e-6);
}

TEST(TrackPoseOnLandmarks, UsesCameraOneAndSurvivesOutliers) {
  const Scene scene(2);
  const Eigen::Isometry3d truth = Scene::BodyPose(2.5);
  std::vector<FeatureObservation> obs = scene.Observe(truth);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (size_t i = 0; i < obs.size(); i += 8) obs[i].xy = {u(rng), u(rng)};
  const VisualPose pose =
      TrackPoseOnLandmarks(scene.window_, scene.features_, obs,
                           Scene::BodyPose(1.0), VisualTrackerSettings());
  ASSERT_TRUE(pose.ok);
  EXPECT_EQ(pose.landmarks, 120);
  EXPECT_EQ(pose.inliers, 120 - 15);
  // The Huber kernel leaves a little of the 15 outliers' pull.
  EXPECT_LT(PoseError(pose.T_w_b, truth), 2e-3);
}

TEST(TrackPoseOnLandmarks, TooFewLandmarksOrABadGuessIsNotATrack) {
  const Scene scene(1);
  const Eigen::Isometry3d truth = Scene::BodyPose(2.0);
  std::vector<FeatureObservation> obs = scene.Observe(truth);
  VisualTrackerSettings settings;
  settings.min_landmarks = 61;
  EXPECT_FALSE(TrackPoseOnLandmarks(scene.window_, scene.features_, obs,
                                    Scene::BodyPose(1.0), settings)
                   .ok);
  Eigen::Isometry3d nan_guess = Scene::BodyPose(1.0);
  nan_guess.translation().x() = std::nan("");
  EXPECT_FALSE(TrackPoseOnLandmarks(scene.window_, scene.features_, obs,
                                    nan_guess, VisualTrackerSettings())
                   .ok);
  // Unknown features give no landmark.
  for (FeatureObservation& o : obs) o.feature_id += 1000;
  const VisualPose none =
      TrackPoseOnLandmarks(scene.window_, scene.features_, obs,
                           Scene::BodyPose(1.0), VisualTrackerSettings());
  EXPECT_FALSE(none.ok);
  EXPECT_EQ(none.landmarks, 0);
}

}  // namespace
}  // namespace vio
