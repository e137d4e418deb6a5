// What landmarks.reanchored_tracks does with the landmarks of a keyframe that
// leaves the window (estimator_options.h): which of their sightings enter the
// problem and which are folded into the prior at the next marginalisations.

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "estimator/feature_manager.h"
#include "estimator/window.h"
#include "estimator/window_problem.h"
#include "geometry/feature_observation.h"

namespace vio {
namespace {

std::vector<int64_t> Frames(const std::vector<SightingRef>& sightings) {
  std::vector<int64_t> frames;
  for (const SightingRef& s : sightings) frames.push_back(s.frame_id);
  return frames;
}

// One landmark 4 m in front of frames 0, 1, 2, ... (1 m apart along x), seen
// exactly by each (mono). When frame 0 leaves, the landmark's factors to
// frames 1 and 2 are folded into the prior and it is re-anchored in frame 1.
class ReanchoredTrack : public ::testing::TestWithParam<ReanchoredTracks> {
 protected:
  void SetUp() override {
    settings_.reanchored_tracks = GetParam();
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

  // What Estimator::MarginalizeOldest and Slide do when the oldest frame
  // leaves: the folds recorded, the frame removed (the landmark re-anchored,
  // its depth carried over). Returns the sightings folded.
  std::vector<SightingRef> RemoveOldest(const WindowProblem& problem) {
    const std::vector<SightingRef> folded =
        problem.FoldedSightings(OutlierReport(), {});
    for (const SightingRef& s : folded) {
      features_.RecordFold(s.feature_id, s.frame_id, s.camera);
    }
    features_.RemoveFrame(window_.frames.front()->id,
                          [this](int64_t frame_id, int camera) {
                            return window_.T_w_c(frame_id, camera);
                          });
    window_.frames.pop_front();
    return folded;
  }

  // Frame 0 leaves; the landmark goes on in frame 3.
  void FirstMarginalization() {
    WindowProblem problem(&window_, &features_, settings_);
    ASSERT_EQ(problem.AddVisualFactors(), 1);
    ASSERT_EQ(problem.num_visual_residuals(), 2);
    ASSERT_EQ(problem.MarginalizedLandmarks(OutlierReport()),
              std::vector<int64_t>{1});
    ASSERT_EQ(Frames(RemoveOldest(problem)), (std::vector<int64_t>{1, 2}));
    const Landmark& l = features_.landmarks().at(1);
    ASSERT_TRUE(l.triangulated);  // re-anchored in frame 1
    ASSERT_EQ(l.anchor().frame_id, 1);
    ASSERT_NEAR(l.inverse_depth, 1.0 / point_.z(), 1e-12);
    AddFrame(3);
  }

  const Eigen::Vector3d point_{0.3, 0.2, 4.0};
  WindowProblemSettings settings_;
  Window window_;
  FeatureManager features_{1};
};

using ReuseTrack = ReanchoredTrack;
using SkipPriorTrack = ReanchoredTrack;
using FoldOnceTrack = ReanchoredTrack;

TEST_P(ReuseTrack, FoldsASightingAgainWithEachAnchor) {
  FirstMarginalization();
  WindowProblem problem(&window_, &features_, settings_);
  EXPECT_EQ(problem.AddVisualFactors(), 1);
  EXPECT_EQ(problem.num_visual_residuals(), 2);  // frames 2 and 3
  const MarginalizationProblem m =
      problem.OldestFrameMarginalization(OutlierReport());
  EXPECT_EQ(m.residual_blocks.size(), 2u);
  EXPECT_EQ(Frames(RemoveOldest(problem)), (std::vector<int64_t>{2, 3}));
  EXPECT_EQ(features_.landmarks().at(1).sightings.front().folds, 2);
}
INSTANTIATE_TEST_SUITE_P(Reuse, ReuseTrack,
                         ::testing::Values(ReanchoredTracks::kReuse));

TEST_P(SkipPriorTrack, SightingsFoldedBeforeDoNotEnterAgain) {
  WindowProblem first(&window_, &features_, settings_);
  ASSERT_EQ(first.AddVisualFactors(), 1);
  RemoveOldest(first);
  {
    // Frame 2's sighting is in the prior: nothing new about the landmark.
    WindowProblem problem(&window_, &features_, settings_);
    EXPECT_EQ(problem.AddVisualFactors(), 0);
    EXPECT_EQ(problem.num_visual_residuals(), 0);
  }
  AddFrame(3);
  WindowProblem problem(&window_, &features_, settings_);
  EXPECT_EQ(problem.AddVisualFactors(), 1);
  EXPECT_EQ(problem.num_visual_residuals(), 1);  // frame 3 only
}
INSTANTIATE_TEST_SUITE_P(SkipPrior, SkipPriorTrack,
                         ::testing::Values(ReanchoredTracks::kSkipPrior));

TEST_P(FoldOnceTrack, KeepsFoldedSightingsButFoldsThemOnce) {
  FirstMarginalization();
  WindowProblem problem(&window_, &features_, settings_);
  EXPECT_EQ(problem.AddVisualFactors(), 1);
  // Frame 2's sighting, folded with frame 0's anchor, stays a factor (the
  // link between the track's past and its future), as with reuse.
  EXPECT_EQ(problem.num_visual_residuals(), 2);
  const MarginalizationProblem m =
      problem.OldestFrameMarginalization(OutlierReport());
  // Only frame 3's factor goes into the prior; the landmark's inverse depth
  // is marginalised with it (no IMU factor here: frame 1's speed-bias stays).
  EXPECT_EQ(m.residual_blocks.size(), 1u);
  const std::vector<const double*> marginalized = {
      window_.frames.front()->pose.data(),
      &features_.landmarks().at(1).inverse_depth};
  EXPECT_EQ(m.marginalized, marginalized);
  int left_out = -1;
  EXPECT_EQ(Frames(problem.FoldedSightings(OutlierReport(), {}, &left_out)),
            std::vector<int64_t>{3});
  EXPECT_EQ(left_out, 1);
  RemoveOldest(problem);
  // Every sighting still in the window was folded exactly once.
  for (const Sighting& s : features_.landmarks().at(1).sightings) {
    EXPECT_EQ(s.folds, 1) << "frame " << s.frame_id;
  }
}

TEST_P(FoldOnceTrack, LeavesALandmarkWithNothingNewOutOfTheMarginalization) {
  // Frame 0 leaves; frame 1, the new anchor, leaves next with no new
  // sighting: the factor to frame 2 was folded already, so the landmark has
  // nothing to fold and its inverse depth stays in the window.
  WindowProblem first(&window_, &features_, settings_);
  ASSERT_EQ(first.AddVisualFactors(), 1);
  RemoveOldest(first);
  WindowProblem problem(&window_, &features_, settings_);
  EXPECT_EQ(problem.AddVisualFactors(), 1);  // still a factor of the problem
  const MarginalizationProblem m =
      problem.OldestFrameMarginalization(OutlierReport());
  EXPECT_TRUE(m.residual_blocks.empty());
  EXPECT_TRUE(m.marginalized.empty());
  EXPECT_TRUE(problem.MarginalizedLandmarks(OutlierReport()).empty());
}
INSTANTIATE_TEST_SUITE_P(FoldOnce, FoldOnceTrack,
                         ::testing::Values(ReanchoredTracks::kFoldOnce));

TEST(ReanchoredTracksDropLeaving, LeavesAContinuingTrackOutOfThePrior) {
  // The landmark is seen in the newest frame (2), so it is not marginalised;
  // its sighting in frame 0 leaves with the frame.
  Window window;
  window.num_cameras = 1;
  window.extrinsics[0] = {0, 0, 0, 0, 0, 0, 1};
  FeatureManager features(1);
  const Eigen::Vector3d point(0.3, 0.2, 4.0);
  for (int64_t id = 0; id < 3; ++id) {
    auto frame = std::make_unique<WindowFrame>();
    frame->id = id;
    frame->pose[kPoseP] = static_cast<double>(id);
    window.frames.push_back(std::move(frame));
    const Eigen::Vector3d p_c = point - Eigen::Vector3d(id, 0, 0);
    FeatureObservation o;
    o.feature_id = 1;
    o.xy = p_c.head<2>() / p_c.z();
    features.AddFrame(id, {o});
  }
  features.landmarks().at(1).triangulated = true;
  features.landmarks().at(1).inverse_depth = 1.0 / point.z();
  WindowProblemSettings settings;
  settings.reanchored_tracks = ReanchoredTracks::kDropLeaving;
  WindowProblem problem(&window, &features, settings);
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
  features.RemoveSighting(1, 2, 0);
  WindowProblem ended(&window, &features, settings);
  ASSERT_EQ(ended.AddVisualFactors(), 1);
  EXPECT_TRUE(ended.ContinuingLandmarks().empty());
}

}  // namespace
}  // namespace vio
