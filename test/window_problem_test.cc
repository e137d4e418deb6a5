#include "estimator/window_problem.h"

#include <ceres/normal_prior.h>
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

TEST_F(WindowProblemOutliers, CountsEveryResidualNotOnlyTheVisualOnes) {
  // The summary's work per step (vio_replay's "solver work per step"): the
  // two landmarks' sightings in frame 1 plus a frame link on frame 0's pose.
  WindowProblem problem(&window_, &features_, WindowProblemSettings());
  ASSERT_EQ(problem.AddVisualFactors(), 2);
  problem.AddFrameLink(std::make_unique<ceres::NormalPrior>(
                           Eigen::Matrix<double, 7, 7>::Identity(),
                           Eigen::Map<const Eigen::Matrix<double, 7, 1>>(
                               window_.frames.front()->pose.data())),
                       {window_.frames.front()->pose.data()},
                       /*start_frame=*/0);
  EXPECT_EQ(problem.num_visual_residuals(), 2);
  EXPECT_EQ(problem.num_residuals(), 3);
}

}  // namespace
}  // namespace vio
