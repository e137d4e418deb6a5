// landmarks.max_world_points in the window problem
// (estimator/window_problem_points.cc, CapWorldPoints): when more world
// points would stay after the oldest frame's marginalisation than the bound,
// the excess (last sighting oldest first) is marginalised with every
// sighting it has in the window, so that the prior is what the unbounded
// prior followed by the marginalisation of those points would give (a
// Schur complement is the same in one step or two), not what dropping them
// would give.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <vector>

#include "estimator/feature_manager.h"
#include "estimator/marginalization.h"
#include "estimator/state_prior.h"
#include "estimator/window.h"
#include "estimator/window_problem.h"
#include "factors/robust_kernel.h"
#include "factors/world_point_factor.h"
#include "geometry/feature_observation.h"

namespace vio {
namespace {

// Three tracks, all anchored in frame 0: kLong seen in frames 0-3 (still
// tracked in the newest frame), kShort in 0-1 and kMid in 0-2 (both lost by
// the tracker before the newest frame).
constexpr int64_t kLong = 3;
constexpr int64_t kShort = 4;
constexpr int64_t kMid = 5;

// Four frames 0.5 m apart along x and slightly rotated, a mono camera on the
// body looking along +z, a state prior on frame 0; the sightings are the
// exact projections plus a fixed offset of a few pixels so that the robust
// kernel and the residuals are not trivially zero.
class PointCap : public ::testing::Test {
 protected:
  void SetUp() override {
    window_.num_cameras = 1;
    window_.extrinsics[0] = {0, 0, 0, 0, 0, 0, 1};
    const std::map<int64_t, int> last = {{kLong, 3}, {kShort, 1}, {kMid, 2}};
    for (int64_t id = 0; id < 4; ++id) {
      auto frame = std::make_unique<WindowFrame>();
      frame->id = id;
      frame->pose[kPoseP] = 0.5 * static_cast<double>(id);
      frame->pose[kPoseP + 1] = 0.05 * static_cast<double>(id * id);
      const Eigen::Quaterniond q(
          Eigen::AngleAxisd(0.03 * static_cast<double>(id),
                            Eigen::Vector3d(0.2, 1.0, 0.1).normalized()));
      frame->q_w_b() = q;
      frame->keyframe = true;
      window_.frames.push_back(std::move(frame));
      std::vector<FeatureObservation> observations;
      for (const auto& [feature, last_frame] : last) {
        if (id > last_frame) continue;
        const Eigen::Vector3d p_c =
            window_.T_w_c(id, 0).inverse() * points_.at(feature);
        FeatureObservation o;
        o.feature_id = feature;
        o.xy = p_c.head<2>() / p_c.z() +
               Eigen::Vector2d(0.004, -0.003) * static_cast<double>(id % 2);
        observations.push_back(o);
      }
      features_.AddFrame(id, observations);
    }
    for (auto& [feature, l] : features_.landmarks()) {
      l.triangulated = true;
      l.inverse_depth = 1.0 / points_.at(feature).z();
    }
    WindowFrame& f0 = *window_.frames.front();
    prior_ = MakeStatePrior(f0.pose.data(), f0.speed_bias.data(),
                            StatePriorOptions(), 0.3);
    prior_blocks_ = {f0.pose.data(), f0.speed_bias.data()};
  }

  WindowProblemSettings Settings(int max_points) const {
    WindowProblemSettings s;
    s.keep_points = true;
    s.point_first_estimates = true;
    s.max_points = max_points;
    return s;
  }

  const std::map<int64_t, Eigen::Vector3d> points_ = {
      {kLong, {0.3, 0.2, 4.0}}, {kShort, {-0.5, 0.1, 3.0}},
      {kMid, {0.8, -0.4, 5.0}}};
  Window window_;
  FeatureManager features_{1};
  std::unique_ptr<MarginalizationPrior> prior_;
  std::vector<double*> prior_blocks_;
};

// H* of `result` rearranged in the order of `blocks` (tangent sizes: 6 for a
// pose, 3 for a point), so that two results can be compared block by block.
Eigen::MatrixXd InformationIn(const MarginalizationResult& result,
                              const std::vector<const double*>& blocks) {
  std::vector<int> offset, size;
  int n = 0;
  for (size_t b = 0; b < result.kept_parameter_blocks.size(); ++b) {
    offset.push_back(n);
    size.push_back(result.kept_blocks[b].TangentSize());
    n += size.back();
  }
  std::vector<int> order;  // result's block index, in `blocks` order
  for (const double* block : blocks) {
    const auto it = std::find(result.kept_parameter_blocks.begin(),
                              result.kept_parameter_blocks.end(), block);
    if (it == result.kept_parameter_blocks.end()) return Eigen::MatrixXd();
    order.push_back(static_cast<int>(it - result.kept_parameter_blocks.begin()));
  }
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
  int row = 0;
  for (const int a : order) {
    int col = 0;
    for (const int b : order) {
      out.block(row, col, size[a], size[b]) =
          result.information.block(offset[a], offset[b], size[a], size[b]);
      col += size[b];
    }
    row += size[a];
  }
  return out;
}

TEST_F(PointCap, TheExcessLeavesLastSightingOldestFirst) {
  const FeatureManager fresh = features_;
  WindowProblem problem(&window_, &features_, Settings(1));
  problem.AddPrior(prior_.get(), prior_blocks_);
  problem.AddVisualFactors();
  const MarginalizationProblem m =
      problem.OldestFrameMarginalization(OutlierReport());
  // Three tracks go on past frame 0 and become world points; one may stay:
  // the one still seen in the newest frame.
  EXPECT_EQ(problem.capped_points(), (std::vector<int64_t>{kShort, kMid}));
  auto marginalized = [&m](int64_t id, const FeatureManager& f) {
    const double* p_w = f.landmarks().at(id).p_w.data();
    return std::count(m.marginalized.begin(), m.marginalized.end(), p_w);
  };
  EXPECT_EQ(marginalized(kShort, features_), 1);
  EXPECT_EQ(marginalized(kMid, features_), 1);
  EXPECT_EQ(marginalized(kLong, features_), 0);
  // Folded: the prior, kLong's frame-0 sighting, and every sighting of the
  // two capped points (2 + 3).
  EXPECT_EQ(m.residual_blocks.size(), 1u + 1u + 2u + 3u);
  // Without a bound, or with room for all three, nothing is capped.
  for (const int max_points : {0, 3}) {
    SCOPED_TRACE(max_points);
    FeatureManager features = fresh;
    WindowProblem unbounded(&window_, &features, Settings(max_points));
    unbounded.AddPrior(prior_.get(), prior_blocks_);
    unbounded.AddVisualFactors();
    const MarginalizationProblem u =
        unbounded.OldestFrameMarginalization(OutlierReport());
    EXPECT_TRUE(unbounded.capped_points().empty());
    EXPECT_EQ(u.residual_blocks.size(), 1u + 3u);
  }
}

TEST_F(PointCap, CappedPointsAreMarginalisedNotDropped) {
  // Two steps: the unbounded marginalisation of frame 0 (only its sightings
  // folded, every point kept), then the two points the bound would cap
  // marginalised against that prior with their later sightings, made here
  // from the factor's own constructor. The bound in one step must give the
  // same information on the blocks that stay.
  FeatureManager two_step_features = features_;
  MarginalizationResult first;
  std::vector<std::unique_ptr<ceres::CostFunction>> later;
  MarginalizationProblem second;
  {
    WindowProblem problem(&window_, &two_step_features, Settings(0));
    problem.AddPrior(prior_.get(), prior_blocks_);
    problem.AddVisualFactors();
    first = Marginalize(problem.OldestFrameMarginalization(OutlierReport()));
    ASSERT_TRUE(first.ok());
    ASSERT_TRUE(problem.capped_points().empty());
  }
  const std::unique_ptr<MarginalizationPrior> prior1 = first.MakePrior();
  const PoseManifold pose_manifold;
  second.parameter_blocks = KeptParameterBlocks(first, &pose_manifold);
  second.residual_blocks.push_back(PriorResidualBlock(first, prior1.get()));
  const WindowProblemSettings settings = Settings(0);
  const std::unique_ptr<ceres::LossFunction> loss =
      MakeLossFunction(settings.visual.robust_kernel);
  for (const int64_t id : {kShort, kMid}) {
    Landmark& l = two_step_features.landmarks().at(id);
    ASSERT_TRUE(l.world_point);
    for (const Sighting& s : l.sightings) {
      if (s.frame_id == 0) continue;
      later.push_back(std::make_unique<WorldPointReprojectionFactor>(
          s.xy, settings.visual.SqrtInformation(settings.focal_px[0]),
          l.p_w_first.data()));
      second.residual_blocks.push_back(
          {later.back().get(),
           loss.get(),
           {window_.Find(s.frame_id)->pose.data(), window_.extrinsics[0].data(),
            l.p_w.data()}});
    }
    second.marginalized.push_back(l.p_w.data());
  }
  for (const int64_t frame : {1, 2}) {
    second.parameter_blocks.push_back(
        {window_.Find(frame)->pose.data(), 7, &pose_manifold, false});
  }
  second.parameter_blocks.push_back(
      {window_.extrinsics[0].data(), 7, &pose_manifold, true});
  const MarginalizationResult two_steps = Marginalize(second);
  ASSERT_TRUE(two_steps.ok());

  // The bound in one step, on the same values (the scene's own features).
  WindowProblem problem(&window_, &features_, Settings(1));
  problem.AddPrior(prior_.get(), prior_blocks_);
  problem.AddVisualFactors();
  const MarginalizationResult one_step =
      Marginalize(problem.OldestFrameMarginalization(OutlierReport()));
  ASSERT_TRUE(one_step.ok());

  // The blocks that stay: poses 1 and 2 (seen by the capped points) and the
  // kept point, in each case; frame 3's pose only in a factor still live.
  const std::vector<const double*> kept_two = {
      window_.Find(1)->pose.data(), window_.Find(2)->pose.data(),
      two_step_features.landmarks().at(kLong).p_w.data()};
  const std::vector<const double*> kept_one = {
      window_.Find(1)->pose.data(), window_.Find(2)->pose.data(),
      features_.landmarks().at(kLong).p_w.data()};
  ASSERT_EQ(one_step.kept_parameter_blocks.size(), 3u);
  ASSERT_EQ(two_steps.kept_parameter_blocks.size(), 3u);
  const Eigen::MatrixXd h_one = InformationIn(one_step, kept_one);
  const Eigen::MatrixXd h_two = InformationIn(two_steps, kept_two);
  ASSERT_EQ(h_one.rows(), 15);
  ASSERT_EQ(h_two.rows(), 15);
  EXPECT_LT((h_one - h_two).norm(), 1e-8 * h_two.norm())
      << "one step:\n" << h_one << "\ntwo steps:\n" << h_two;
}

}  // namespace
}  // namespace vio
