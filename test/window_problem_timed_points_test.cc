// World points with the time offset estimated in the window problem
// (estimator/window_problem_points.cc): the factors folded into the prior at
// a conversion and the live ones after it are timed, on the t_d block (kept,
// never marginalised), each sighting shifted along the image velocity of
// the camera that saw it. The velocity expected here comes from a finite
// difference of the point's projection under the frame's own motion, not
// from estimator/image_velocity.h.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "estimator/feature_manager.h"
#include "estimator/window.h"
#include "estimator/window_problem.h"
#include "geometry/feature_observation.h"
#include "geometry/so3.h"

namespace vio {
namespace {

constexpr int64_t kId = 7;
constexpr double kTdAtStamp = 0.002;  // [s]

// Three stereo frames 1 m apart along x, moving at v_w and turning at w_b;
// camera 1 is 11 cm to the side and turned 20 deg about its axis (so its image
// velocity differs from camera 0's). One landmark seen exactly by both
// cameras of every frame.
class TimedPoints : public ::testing::Test {
 protected:
  void SetUp() override {
    window_.num_cameras = 2;
    window_.extrinsics[0] = {0, 0, 0, 0, 0, 0, 1};
    const Eigen::Quaterniond q1(
        Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitZ()));
    window_.extrinsics[1] = {0.11, 0.0, 0.0, q1.x(), q1.y(), q1.z(), q1.w()};
    window_.t_d = kTdAtStamp;
    for (int64_t id = 0; id < 3; ++id) {
      auto frame = std::make_unique<WindowFrame>();
      frame->id = id;
      frame->pose[kPoseP] = static_cast<double>(id);
      frame->t_d_at_stamp = kTdAtStamp;
      frame->v_w() = v_w_;
      frame->gyr_b = w_b_;  // the gyroscope bias is zero
      window_.frames.push_back(std::move(frame));
      std::vector<FeatureObservation> obs;
      for (int c = 0; c < 2; ++c) {
        FeatureObservation o;
        o.feature_id = kId;
        o.camera = c;
        o.xy = Project(id, c, 0.0);
        obs.push_back(o);
      }
      features_.AddFrame(id, obs);
    }
    Landmark& l = features_.landmarks().at(kId);
    l.triangulated = true;
    l.inverse_depth = 1.0 / point_.z();  // camera 0 of frame 0 is the world
  }

  // The point's normalised projection in camera c of frame id, dt [s] after
  // the pose's time, the frame moving on with v_w and w_b.
  Eigen::Vector2d Project(int64_t id, int c, double dt) const {
    Eigen::Isometry3d T_w_b = Eigen::Isometry3d::Identity();
    T_w_b.linear() = Exp(w_b_ * dt);
    T_w_b.translation() = Eigen::Vector3d(id, 0, 0) + v_w_ * dt;
    const Eigen::Vector3d p_c = (T_w_b * window_.T_b_c(c)).inverse() * point_;
    return p_c.head<2>() / p_c.z();
  }
  Eigen::Vector2d Velocity(int64_t id, int c) const {
    const double h = 1e-6;
    return (Project(id, c, h) - Project(id, c, -h)) / (2.0 * h);
  }

  WindowProblemSettings Settings() const {
    WindowProblemSettings s;
    s.keep_points = true;
    s.point_first_estimates = true;
    s.estimate_time_offset = true;
    return s;
  }

  // The residual of cost at blocks with t_d (the last block) at t_d.
  Eigen::Vector2d At(const ceres::CostFunction& cost,
                     const std::vector<double*>& blocks, double t_d) {
    EXPECT_EQ(blocks.back(), &window_.t_d);
    const double saved = window_.t_d;
    window_.t_d = t_d;
    Eigen::Vector2d r;
    EXPECT_TRUE(cost.Evaluate(blocks.data(), r.data(), nullptr));
    window_.t_d = saved;
    return r;
  }

  // Each factor's shift: r(t_d) - r(t_d_k) = sqrt_info (t_d - t_d_k) v_k,
  // v_k the image velocity of its own camera.
  void ExpectShiftedAlongItsCamera(const ceres::CostFunction& cost,
                                   const std::vector<double*>& blocks) {
    ASSERT_EQ(blocks.size(), 4u);
    int64_t id = -1;
    for (const auto& f : window_.frames) {
      if (f->pose.data() == blocks[0]) id = f->id;
    }
    ASSERT_GE(id, 0);
    const int c = blocks[1] == window_.extrinsics[1].data() ? 1 : 0;
    const double sqrt_info = Settings().visual.SqrtInformation(
        Settings().focal_px[c]);
    const double delta = 0.004;
    EXPECT_LT(At(cost, blocks, kTdAtStamp).norm(), 1e-9);
    const Eigen::Vector2d shift = At(cost, blocks, kTdAtStamp + delta);
    const Eigen::Vector2d expected = sqrt_info * delta * Velocity(id, c);
    EXPECT_LT((shift - expected).norm(), 1e-6 * sqrt_info)
        << "frame " << id << " camera " << c << ": " << shift.transpose()
        << " expected " << expected.transpose();
    ++checked_[c];
  }

  const Eigen::Vector3d point_{1.5, -0.8, 4.0};
  const Eigen::Vector3d v_w_{2.0, 0.5, 0.3};
  const Eigen::Vector3d w_b_{0.1, 0.2, 0.8};
  Window window_;
  FeatureManager features_{2};
  int checked_[2] = {0, 0};
};

TEST_F(TimedPoints, FoldedAndLiveFactorsAreShiftedAlongTheirOwnCamera) {
  // The two cameras' velocities differ enough for the check to tell them
  // apart (a factor given camera 0's velocity for camera 1 fails it).
  ASSERT_GT((Velocity(0, 1) - Velocity(0, 0)).norm(), 0.05)
      << Velocity(0, 0).transpose() << " | " << Velocity(0, 1).transpose();
  {
    WindowProblem problem(&window_, &features_, Settings());
    problem.AddVisualFactors();
    const MarginalizationProblem m =
        problem.OldestFrameMarginalization(OutlierReport());
    ASSERT_TRUE(features_.landmarks().at(kId).world_point);
    // Frame 0's two sightings are folded, timed, on t_d.
    ASSERT_EQ(m.residual_blocks.size(), 2u);
    for (const auto& r : m.residual_blocks) {
      ExpectShiftedAlongItsCamera(*r.cost, r.parameter_blocks);
    }
    // t_d is in the prior's blocks, kept.
    EXPECT_EQ(std::count_if(m.parameter_blocks.begin(),
                            m.parameter_blocks.end(),
                            [this](const auto& b) {
                              return b.values == &window_.t_d;
                            }),
              1);
    EXPECT_EQ(std::count(m.marginalized.begin(), m.marginalized.end(),
                         &window_.t_d),
              0);
    features_.RemoveFrame(0, [this](int64_t frame, int camera) {
      return window_.T_w_c(frame, camera);
    });
    window_.frames.pop_front();
  }
  // The live factors of frames 1 and 2, both cameras.
  WindowProblem problem(&window_, &features_, Settings());
  EXPECT_EQ(problem.AddVisualFactors(), 1);
  ASSERT_EQ(problem.num_visual_residuals(), 4);
  const std::unique_ptr<ceres::Problem> ceres = problem.CeresProblem();
  std::vector<ceres::ResidualBlockId> ids;
  ceres->GetResidualBlocks(&ids);
  ASSERT_EQ(ids.size(), 4u);
  for (const ceres::ResidualBlockId id : ids) {
    std::vector<double*> blocks;
    ceres->GetParameterBlocksForResidualBlock(id, &blocks);
    ExpectShiftedAlongItsCamera(*ceres->GetCostFunctionForResidualBlock(id),
                                blocks);
  }
  EXPECT_EQ(checked_[0], 3);
  EXPECT_EQ(checked_[1], 3);
}

}  // namespace
}  // namespace vio
