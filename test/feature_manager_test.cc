#include "estimator/feature_manager.h"

#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <random>

namespace vio {
namespace {

// A camera moving along world +y while looking along +x, frame k at
// y = 0.2 k [m]; points 3-8 m ahead. Camera 1 sits 0.11 m to the right.
class Scene {
 public:
  explicit Scene(int num_points) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < num_points; ++i) {
      points_w_.push_back({5.5 + 2.5 * u(rng), 1.0 + 2.0 * u(rng), u(rng)});
    }
  }
  Eigen::Isometry3d T_w_c(int64_t frame_id, int camera) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    T.translation() = Eigen::Vector3d(0, 0.2 * frame_id - 0.11 * camera, 0);
    return T;
  }
  // Observations of points [first, last) in the frame.
  std::vector<FeatureObservation> Observe(int64_t frame_id, int first, int last,
                                          int cameras = 1) const {
    std::vector<FeatureObservation> out;
    for (int cam = 0; cam < cameras; ++cam) {
      for (int i = first; i < last; ++i) {
        const Eigen::Vector3d p_c =
            T_w_c(frame_id, cam).inverse() * points_w_[i];
        FeatureObservation o;
        o.feature_id = i;
        o.camera = cam;
        o.xy = p_c.head<2>() / p_c.z();
        out.push_back(o);
      }
    }
    return out;
  }
  const Eigen::Vector3d& point(int i) const { return points_w_[i]; }
  CameraPoseFn PoseFn() const {
    return [this](int64_t f, int c) { return T_w_c(f, c); };
  }

 private:
  std::vector<Eigen::Vector3d> points_w_;
};

TEST(FeatureManager, CountsTrackedFeaturesAndSkipsInvalidObservations) {
  const Scene scene(30);
  FeatureManager fm(1);
  FrameAddStats s = fm.AddFrame(0, scene.Observe(0, 0, 20));
  EXPECT_EQ(s.added, 20);
  EXPECT_EQ(s.tracked, 0);
  auto obs = scene.Observe(1, 10, 30);
  obs[0].xy.x() = std::numeric_limits<double>::quiet_NaN();  // feature 10
  obs.push_back(obs[1]);  // duplicate of feature 11
  obs.push_back(obs[2]);
  obs.back().camera = 1;  // a camera a mono manager does not have
  s = fm.AddFrame(1, obs);
  EXPECT_EQ(s.added, 19);
  EXPECT_EQ(s.tracked, 9);  // features 11..19
  EXPECT_EQ(s.skipped, 3);
  EXPECT_EQ(fm.landmarks().size(), 30u);
  EXPECT_EQ(fm.landmarks().at(10).sightings.size(), 1u);
  EXPECT_THROW(fm.AddFrame(1, {}), std::invalid_argument);
}

TEST(FeatureManager, TriangulatesNoiseFreeLandmarksExactly) {
  const Scene scene(40);
  FeatureManager fm(2);
  for (int64_t f = 0; f < 3; ++f) fm.AddFrame(f, scene.Observe(f, 0, 40, 2));
  EXPECT_EQ(fm.TriangulateNew(scene.PoseFn(), TriangulationOptions()), 40);
  for (const auto& [id, l] : fm.landmarks()) {
    ASSERT_TRUE(l.triangulated);
    EXPECT_LT((FeatureManager::WorldPoint(l, scene.PoseFn()) -
               scene.point(static_cast<int>(id)))
                  .norm(),
              1e-8);
  }
}

TEST(FeatureManager, StereoPairAloneGivesDepthInOneFrame) {
  const Scene scene(10);
  FeatureManager fm(2);
  fm.AddFrame(0, scene.Observe(0, 0, 10, 2));
  EXPECT_EQ(fm.TriangulateNew(scene.PoseFn(), TriangulationOptions()), 10);
  const Landmark& l = fm.landmarks().at(3);
  EXPECT_EQ(l.anchor().camera, 0);
  const double depth_true = (scene.T_w_c(0, 0).inverse() * scene.point(3)).z();
  EXPECT_NEAR(1.0 / l.inverse_depth, depth_true, 1e-8);
}

TEST(FeatureManager, ReanchoringKeepsTheWorldPoint) {
  const Scene scene(20);
  FeatureManager fm(1);
  for (int64_t f = 0; f < 4; ++f) fm.AddFrame(f, scene.Observe(f, 0, 20));
  fm.AddFrame(4, scene.Observe(4, 0, 5));
  ASSERT_EQ(fm.TriangulateNew(scene.PoseFn(), TriangulationOptions()), 20);
  // Perturb one depth so re-anchoring must carry an estimate, not the truth.
  fm.landmarks().at(7).inverse_depth *= 1.1;
  const Eigen::Vector3d p7 =
      FeatureManager::WorldPoint(fm.landmarks().at(7), scene.PoseFn());
  fm.RemoveFrame(0, scene.PoseFn());
  for (const auto& [id, l] : fm.landmarks()) {
    EXPECT_EQ(l.anchor().frame_id, 1);
    if (id == 7) {
      // The new bearing is the new anchor's measurement, so what carries
      // over from the estimate is its depth in the new anchor camera.
      EXPECT_NEAR(1.0 / l.inverse_depth, (scene.T_w_c(1, 0).inverse() * p7).z(),
                  1e-9);
      continue;
    }
    EXPECT_LT((FeatureManager::WorldPoint(l, scene.PoseFn()) -
               scene.point(static_cast<int>(id)))
                  .norm(),
              1e-9);
  }
  // Landmarks whose last sighting leaves are deleted.
  for (int64_t f = 1; f < 4; ++f) fm.RemoveFrame(f, scene.PoseFn());
  EXPECT_EQ(fm.landmarks().size(), 5u);
  EXPECT_EQ(fm.landmarks().at(0).sightings.size(), 1u);
}

TEST(FeatureManager, AnchorsInCameraZeroOnly) {
  const Scene scene(5);
  FeatureManager fm(2);
  auto frame0 = scene.Observe(0, 0, 5, 2);
  // Feature 0: camera 1 only in frame 0, both cameras in frame 1.
  frame0.erase(frame0.begin());
  fm.AddFrame(0, frame0);
  fm.AddFrame(1, scene.Observe(1, 0, 5, 2));
  const Landmark& l0 = fm.landmarks().at(0);
  EXPECT_EQ(l0.sightings.front().camera, 1);
  EXPECT_EQ(l0.anchor().frame_id, 1);
  EXPECT_EQ(l0.anchor().camera, 0);
  ASSERT_EQ(fm.TriangulateNew(scene.PoseFn(), TriangulationOptions()), 5);
  EXPECT_NEAR(1.0 / l0.inverse_depth,
              (scene.T_w_c(1, 0).inverse() * scene.point(0)).z(), 1e-8);
  // With frame 1 gone, feature 0 has no camera-0 sighting left.
  fm.RemoveFrame(1, scene.PoseFn());
  EXPECT_FALSE(fm.landmarks().at(0).HasAnchor());
  EXPECT_FALSE(fm.landmarks().at(0).triangulated);
}

TEST(FeatureManager, RemovingTheAnchorSightingUntriangulates) {
  const Scene scene(3);
  FeatureManager fm(1);
  for (int64_t f = 0; f < 3; ++f) fm.AddFrame(f, scene.Observe(f, 0, 3));
  ASSERT_EQ(fm.TriangulateNew(scene.PoseFn(), TriangulationOptions()), 3);
  fm.RemoveSighting(0, 1, 0);  // not the anchor: depth kept
  EXPECT_TRUE(fm.landmarks().at(0).triangulated);
  EXPECT_EQ(fm.landmarks().at(0).sightings.size(), 2u);
  fm.RemoveSighting(1, 0, 0);  // the anchor
  EXPECT_FALSE(fm.landmarks().at(1).triangulated);
  EXPECT_EQ(fm.landmarks().at(1).anchor().frame_id, 1);
  fm.RemoveSighting(2, 7, 0);  // absent: nothing happens
  EXPECT_EQ(fm.landmarks().at(2).sightings.size(), 3u);
  fm.RemoveSighting(0, 0, 0);
  fm.RemoveSighting(0, 2, 0);
  EXPECT_EQ(fm.landmarks().count(0), 0u);
}

TEST(DecideKeyframe, UsesParallaxInPixelsAndTrackedCount) {
  const Scene scene(60);
  FeatureManager fm(1);
  fm.AddFrame(0, scene.Observe(0, 0, 60));
  fm.AddFrame(1, scene.Observe(1, 0, 60));
  int common = 0;
  const double parallax = fm.MedianParallax(0, 1, &common);
  EXPECT_EQ(common, 60);
  // 0.2 m sideways at 3-8 m: 0.025-0.067 on the normalised plane.
  EXPECT_GT(parallax, 0.02);
  EXPECT_LT(parallax, 0.07);
  KeyframeOptions options;
  options.min_tracked_features = 50;
  options.min_parallax_px = 1.01 * 460.0 * parallax;
  KeyframeDecision d = DecideKeyframe(fm, 0, 1, 460.0, options);
  EXPECT_FALSE(d.is_keyframe);
  EXPECT_NEAR(d.parallax_px, 460.0 * parallax, 1e-9);
  options.min_parallax_px = 0.99 * 460.0 * parallax;
  EXPECT_TRUE(DecideKeyframe(fm, 0, 1, 460.0, options).is_keyframe);
  options.min_parallax_px = 1e3;
  options.min_tracked_features = 61;
  EXPECT_TRUE(DecideKeyframe(fm, 0, 1, 460.0, options).is_keyframe);
}

TEST(DecideKeyframe, IgnoresAFewTrackerSlips) {
  const Scene scene(60);
  FeatureManager still(1);
  still.AddFrame(0, scene.Observe(0, 0, 60));
  auto obs = scene.Observe(0, 0, 60);
  for (int i = 0; i < 6; ++i) obs[i].xy += Eigen::Vector2d(0.5, -0.4);  // 10 %
  still.AddFrame(1, obs);
  KeyframeOptions options;
  const KeyframeDecision d = DecideKeyframe(still, 0, 1, 460.0, options);
  EXPECT_EQ(d.parallax_px, 0.0);
  EXPECT_FALSE(d.is_keyframe);
}

}  // namespace
}  // namespace vio
