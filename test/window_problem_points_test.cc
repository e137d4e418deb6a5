// landmarks.reanchored_tracks keep_point in the window problem
// (estimator/window_problem_points.cc): a track whose anchor leaves becomes
// a world point, each sighting is folded into the prior once, and the point
// leaves the prior with its last sighting.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "estimator/feature_manager.h"
#include "estimator/window.h"
#include "estimator/window_problem.h"
#include "geometry/feature_observation.h"

namespace vio {
namespace {

constexpr int64_t kId = 7;

// Three frames 1 m apart along x, cameras on the body looking along +z; one
// landmark 4 m in front seen exactly by all three.
class KeepPoint : public ::testing::Test {
 protected:
  void SetUp() override {
    window_.num_cameras = 1;
    window_.extrinsics[0] = {0, 0, 0, 0, 0, 0, 1};
    for (int64_t id = 0; id < 3; ++id) {
      auto frame = std::make_unique<WindowFrame>();
      frame->id = id;
      frame->pose[kPoseP] = static_cast<double>(id);  // x = id [m]
      window_.frames.push_back(std::move(frame));
      const Eigen::Vector3d p_c = point_ - Eigen::Vector3d(id, 0, 0);
      FeatureObservation o;
      o.feature_id = kId;
      o.xy = p_c.head<2>() / p_c.z();
      features_.AddFrame(id, {o});
    }
    Landmark& l = features_.landmarks().at(kId);
    l.triangulated = true;
    l.inverse_depth = 1.0 / point_.z();
  }

  WindowProblemSettings Settings(bool keep) const {
    WindowProblemSettings s;
    s.keep_points = keep;
    return s;
  }
  // The oldest frame's marginalisation, then the frame removed as the
  // estimator does it. Returns the folded residual blocks.
  MarginalizationProblem SlideOldest(bool keep) {
    WindowProblem problem(&window_, &features_, Settings(keep));
    problem.AddVisualFactors();
    const MarginalizationProblem m =
        problem.OldestFrameMarginalization(OutlierReport());
    features_.RemoveFrame(window_.frames.front()->id,
                          [this](int64_t frame, int camera) {
                            return window_.T_w_c(frame, camera);
                          });
    window_.frames.pop_front();
    return m;
  }
  bool Marginalized(const MarginalizationProblem& m, const double* block) {
    return std::count(m.marginalized.begin(), m.marginalized.end(), block) == 1;
  }

  const Eigen::Vector3d point_{0.3, 0.2, 4.0};
  Window window_;
  FeatureManager features_{1};
};

TEST_F(KeepPoint, ReuseFoldsTheRemainingSightingsAgainWithEachAnchor) {
  // What keep_point corrects: frame 2's sighting is folded twice.
  EXPECT_EQ(SlideOldest(false).residual_blocks.size(), 2u);
  EXPECT_EQ(SlideOldest(false).residual_blocks.size(), 1u);
}

TEST_F(KeepPoint, FoldsEachSightingOnceAndKeepsThePoint) {
  double* pose0 = window_.frames[0]->pose.data();
  {
    // The first slide by hand: the problem owns the folded factors.
    WindowProblem problem(&window_, &features_, Settings(true));
    problem.AddVisualFactors();
    const MarginalizationProblem first =
        problem.OldestFrameMarginalization(OutlierReport());
    const Landmark& l = features_.landmarks().at(kId);
    ASSERT_TRUE(l.world_point);
    EXPECT_FALSE(l.triangulated);
    EXPECT_LT((Eigen::Vector3d(l.p_w.data()) - point_).norm(), 1e-12);
    // Only the leaving frame's sighting (the anchor, now with a residual of
    // its own) is folded; the point is kept, the pose leaves.
    ASSERT_EQ(first.residual_blocks.size(), 1u);
    const std::vector<double*> blocks = {
        pose0, window_.extrinsics[0].data(),
        features_.landmarks().at(kId).p_w.data()};
    EXPECT_EQ(first.residual_blocks[0].parameter_blocks, blocks);
    EXPECT_EQ(first.marginalized, std::vector<const double*>{pose0});
    // Its residual is zero at the conversion (the anchor ray was exact).
    Eigen::Vector2d r;
    const double* params[] = {blocks[0], blocks[1], blocks[2]};
    ASSERT_TRUE(
        first.residual_blocks[0].cost->Evaluate(params, r.data(), nullptr));
    EXPECT_LT(r.norm(), 1e-9);
    features_.RemoveFrame(0, [this](int64_t frame, int camera) {
      return window_.T_w_c(frame, camera);
    });
    window_.frames.pop_front();
  }

  // Next: the point has two live sightings, frame 1's is folded, the point
  // stays; then frame 2's, the last, goes with the point.
  {
    WindowProblem problem(&window_, &features_, Settings(true));
    EXPECT_EQ(problem.AddVisualFactors(), 1);
    EXPECT_EQ(problem.num_visual_residuals(), 2);
  }
  const double* p_w = features_.landmarks().at(kId).p_w.data();
  const MarginalizationProblem second = SlideOldest(true);
  EXPECT_EQ(second.residual_blocks.size(), 1u);
  EXPECT_FALSE(Marginalized(second, p_w));
  const MarginalizationProblem third = SlideOldest(true);
  EXPECT_EQ(third.residual_blocks.size(), 1u);
  EXPECT_TRUE(Marginalized(third, p_w));
  // Without sightings it waits, an orphan, for the estimator to forget it.
  EXPECT_EQ(features_.OrphanPoints(), std::vector<int64_t>{kId});
  features_.Forget(kId);
  EXPECT_TRUE(features_.landmarks().empty());
}

TEST_F(KeepPoint, WorldPointsTakePlacesOfMaxLandmarksUnlessOnTop) {
  SlideOldest(true);  // kId: a world point seen in frames 1 and 2
  ASSERT_TRUE(features_.landmarks().at(kId).world_point);
  // A second track, anchored in frame 1 and seen again in frame 2.
  constexpr int64_t kOther = 8;
  Landmark& other = features_.landmarks()[kOther];
  other.feature_id = kOther;
  for (int64_t id : {1, 2}) {
    const Eigen::Vector3d p_c = point_ - Eigen::Vector3d(id, 0.5, 0);
    other.sightings.push_back(
        {id, 0, p_c.head<2>() / p_c.z(), Eigen::Vector2d::Zero()});
  }
  other.triangulated = true;
  other.inverse_depth = 1.0 / point_.z();
  for (const bool in_max : {true, false}) {
    SCOPED_TRACE(in_max);
    WindowProblemSettings s = Settings(true);
    s.max_landmarks = 1;
    s.points_in_max_landmarks = in_max;
    WindowProblem problem(&window_, &features_, s);
    // Counted, the point fills the one place; on top, both are in.
    EXPECT_EQ(problem.AddVisualFactors(), in_max ? 1 : 2);
    EXPECT_EQ(problem.num_visual_residuals(), in_max ? 2 : 3);
  }
}

TEST_F(KeepPoint, ARemovedWorldPointBecomesAnOrphanNotAHole) {
  SlideOldest(true);
  ASSERT_TRUE(features_.landmarks().at(kId).world_point);
  features_.RemoveLandmark(kId);  // the prior still refers to its block
  ASSERT_EQ(features_.landmarks().count(kId), 1u);
  EXPECT_TRUE(features_.landmarks().at(kId).sightings.empty());
  EXPECT_EQ(features_.OrphanPoints(), std::vector<int64_t>{kId});
}

}  // namespace
}  // namespace vio
