#include "estimator/window_problem.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "estimator/feature_manager.h"
#include "estimator/window.h"
#include "geometry/feature_observation.h"

namespace vio {
namespace {

// Two frames 1 m apart along x, cameras on the body, both looking along +z.
// Landmark 1 lies 4 m in front; landmark 2 lies 5 m behind both cameras and
// its sightings are exact projections of that point (x / z, y / z), so its
// reprojection errors are zero: only its inverse depth, negative, says it
// is behind.
class WindowProblemOutliers : public ::testing::Test {
 protected:
  void SetUp() override {
    window_.num_cameras = 1;
    window_.extrinsics[0] = {0, 0, 0, 0, 0, 0, 1};
    for (int64_t id = 0; id < 2; ++id) {
      auto frame = std::make_unique<WindowFrame>();
      frame->id = id;
      frame->pose[kPoseP] = static_cast<double>(id);  // x = id [m]
      window_.frames.push_back(std::move(frame));
    }
    const std::vector<Eigen::Vector3d> points = {{0.3, 0.2, 4.0},
                                                 {0.2, -0.1, -5.0}};
    for (int64_t id = 0; id < 2; ++id) {
      std::vector<FeatureObservation> observations;
      for (size_t k = 0; k < points.size(); ++k) {
        const Eigen::Vector3d p_c =
            points[k] - Eigen::Vector3d(static_cast<double>(id), 0, 0);
        FeatureObservation o;
        o.feature_id = static_cast<int64_t>(k) + 1;
        o.xy = p_c.head<2>() / p_c.z();
        observations.push_back(o);
      }
      features_.AddFrame(id, observations);
    }
    for (size_t k = 0; k < points.size(); ++k) {
      Landmark& l = features_.landmarks().at(static_cast<int64_t>(k) + 1);
      l.triangulated = true;
      l.inverse_depth = 1.0 / points[k].z();  // in the anchor camera (frame 0)
    }
  }

  Window window_;
  FeatureManager features_{1};
};

TEST_F(WindowProblemOutliers, ListsALandmarkBehindItsAnchorApart) {
  WindowProblem problem(&window_, &features_, WindowProblemSettings());
  ASSERT_EQ(problem.AddVisualFactors(), 2);
  const OutlierReport report = problem.Outliers(/*threshold_px=*/5.0);
  EXPECT_EQ(report.behind, std::vector<int64_t>{2});
  EXPECT_TRUE(report.landmarks.empty());
  EXPECT_TRUE(report.sightings.empty());
  EXPECT_TRUE(report.Involves(2));
  EXPECT_FALSE(report.Involves(1));
}

TEST_F(WindowProblemOutliers, ExcludesALandmarkBehindFromTheMarginalization) {
  WindowProblem problem(&window_, &features_, WindowProblemSettings());
  ASSERT_EQ(problem.AddVisualFactors(), 2);
  const OutlierReport report = problem.Outliers(5.0);
  const MarginalizationProblem m = problem.OldestFrameMarginalization(report);
  // The oldest pose and landmark 1's inverse depth only (no IMU factor here,
  // so the speed-bias is in no factor and stays).
  const std::vector<const double*> expected = {
      window_.frames.front()->pose.data(),
      &features_.landmarks().at(1).inverse_depth};
  EXPECT_EQ(m.marginalized, expected);
  EXPECT_EQ(m.residual_blocks.size(), 1u);
}

// One landmark 4 m in front of frames 0 to 3 (1 m apart along x), seen
// exactly by each. Frame 0 leaves with the landmark's factors marginalised:
// its sightings in frames 1 and 2 shaped the prior, only frame 3's is new.
class WindowProblemReanchored : public ::testing::Test {
 protected:
  void SetUp() override {
    window_.num_cameras = 1;
    window_.extrinsics[0] = {0, 0, 0, 0, 0, 0, 1};
    for (int64_t id = 0; id < 3; ++id) AddFrame(id);
    Landmark& l = features_.landmarks().at(1);
    l.triangulated = true;
    l.inverse_depth = 1.0 / point_.z();
  }

  void AddFrame(int64_t id) {
    auto frame = std::make_unique<WindowFrame>();
    frame->id = id;
    frame->pose[kPoseP] = static_cast<double>(id);
    window_.frames.push_back(std::move(frame));
    const Eigen::Vector3d p_c =
        point_ - Eigen::Vector3d(static_cast<double>(id), 0, 0);
    FeatureObservation o;
    o.feature_id = 1;
    o.xy = p_c.head<2>() / p_c.z();
    features_.AddFrame(id, {o});
  }

  // What the estimator does when frame 0 leaves after a marginalisation.
  void MarginalizeOldest(bool mark_in_prior) {
    WindowProblem problem(&window_, &features_, WindowProblemSettings());
    ASSERT_EQ(problem.AddVisualFactors(), 1);
    ASSERT_EQ(problem.num_visual_residuals(), 2);
    const std::vector<int64_t> marginalized =
        problem.MarginalizedLandmarks(OutlierReport());
    ASSERT_EQ(marginalized, std::vector<int64_t>{1});
    if (mark_in_prior) features_.MarkInPrior(1);
    features_.RemoveFrame(0, [this](int64_t frame_id, int camera) {
      return window_.T_w_c(frame_id, camera);
    });
    window_.frames.pop_front();
  }

  const Eigen::Vector3d point_{0.3, 0.2, 4.0};
  Window window_;
  FeatureManager features_{1};
};

TEST_F(WindowProblemReanchored, SightingsInThePriorDoNotEnterAgain) {
  MarginalizeOldest(/*mark_in_prior=*/true);
  const Landmark& l = features_.landmarks().at(1);
  ASSERT_TRUE(l.triangulated);  // re-anchored in frame 1, depth carried over
  EXPECT_EQ(l.anchor().frame_id, 1);
  EXPECT_NEAR(l.inverse_depth, 1.0 / point_.z(), 1e-12);
  {
    // Frame 2's sighting is in the prior: nothing new about the landmark.
    WindowProblem problem(&window_, &features_, WindowProblemSettings());
    EXPECT_EQ(problem.AddVisualFactors(), 0);
    EXPECT_EQ(problem.num_visual_residuals(), 0);
  }
  AddFrame(3);
  WindowProblem problem(&window_, &features_, WindowProblemSettings());
  EXPECT_EQ(problem.AddVisualFactors(), 1);
  EXPECT_EQ(problem.num_visual_residuals(), 1);  // frame 3 only
}

TEST_F(WindowProblemReanchored, UnmarkedSightingsEnterAgain) {
  // VINS-Mono's way (skip_marginalized_sightings false): counted twice.
  MarginalizeOldest(/*mark_in_prior=*/false);
  AddFrame(3);
  WindowProblem problem(&window_, &features_, WindowProblemSettings());
  EXPECT_EQ(problem.AddVisualFactors(), 1);
  EXPECT_EQ(problem.num_visual_residuals(), 2);  // frames 2 and 3
}

TEST_F(WindowProblemReanchored, AContinuingTrackIsLeftOutOfTheMarginalization) {
  // kDropLeaving: the landmark is seen in the newest frame (2), so it is not
  // marginalised; its sighting in frame 0 leaves with the frame.
  WindowProblem problem(&window_, &features_, WindowProblemSettings());
  ASSERT_EQ(problem.AddVisualFactors(), 1);
  const std::vector<int64_t> kept = problem.ContinuingLandmarks();
  ASSERT_EQ(kept, std::vector<int64_t>{1});
  EXPECT_TRUE(problem.MarginalizedLandmarks(OutlierReport(), kept).empty());
  const MarginalizationProblem m =
      problem.OldestFrameMarginalization(OutlierReport(), kept);
  // No IMU factor here: with the landmark left out, no factor touches
  // frame 0, so nothing is marginalised (landmark 1's inverse depth stays).
  EXPECT_TRUE(m.marginalized.empty());
  EXPECT_TRUE(m.residual_blocks.empty());
  // Without frame 2's sighting the track has ended: marginalised.
  features_.RemoveSighting(1, 2, 0);
  WindowProblem ended(&window_, &features_, WindowProblemSettings());
  ASSERT_EQ(ended.AddVisualFactors(), 1);
  EXPECT_TRUE(ended.ContinuingLandmarks().empty());
}

}  // namespace
}  // namespace vio
