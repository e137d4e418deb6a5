// The frontend accuracy reports (eval/track_truth.h, eval/epipolar_error.h)
// on tracks made from exact projections: zero error, and exactly the error
// put into them.

#include "eval/track_truth.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dataset/simulator.h"
#include "eval/epipolar_error.h"
#include "eval/pixel_errors.h"
#include "eval/pose_interpolation.h"
#include "test/testing/expect_error.h"

namespace vio {
namespace {

// A wall at x = 5 (the only surface), seen by cameras looking along +x.
bool CastOnWall(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                Eigen::Vector3d* X) {
  if (d.x() <= 0.0) return false;
  *X = o + (5.0 - o.x()) / d.x() * d;
  return true;
}

// Hidden: a pillar hides the wall's points with y > 0.55 from cameras with
// y < 0 (a stand-in for a box).
bool Visible(const Eigen::Vector3d& eye, const Eigen::Vector3d& X) {
  return !(X.y() > 0.55 && eye.y() < 0.0);
}

Eigen::Isometry3d BodyAt(int k) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.05 * k, 0.04 * k, 1.0);
  T.linear() =
      Eigen::AngleAxisd(0.01 * k, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

// Camera looking along the body's +x (image right = -y, down = -z).
Eigen::Isometry3d CameraInBody(double baseline) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = Eigen::Vector3d(0, -1, 0);
  T.linear().col(1) = Eigen::Vector3d(0, 0, -1);
  T.linear().col(2) = Eigen::Vector3d(1, 0, 0);
  T.translation() = Eigen::Vector3d(0.0, -baseline, 0.0);
  return T;
}

struct Fixture {
  std::vector<CameraModel> cameras;
  std::vector<Eigen::Isometry3d> T_b_c;
  Trajectory poses;
  std::vector<FeatureFrame> frames;
  std::vector<Eigen::Vector3d> points;
};

// 10 frames; features 0..19 on the wall, seen in every frame by cam0 (and
// cam1), with exact pixels.
Fixture ExactTracks() {
  Fixture f;
  f.cameras = {CameraModel(EurocCam0Calibration()),
               CameraModel(EurocCam1Calibration())};
  f.T_b_c = {CameraInBody(0.0), CameraInBody(0.11)};
  for (int i = 0; i < 20; ++i) {
    f.points.emplace_back(5.0, -1.0 + 0.1 * i, 0.6 + 0.04 * i);
  }
  for (int k = 0; k < 10; ++k) {
    const Eigen::Isometry3d T_w_b = BodyAt(k);
    StampedPose pose;
    pose.t_ns = 1000 + 50 * k;
    pose.p_w_b = T_w_b.translation();
    pose.q_w_b = Eigen::Quaterniond(T_w_b.linear());
    f.poses.push_back(pose);
    FeatureFrame frame;
    frame.t_ns = pose.t_ns;
    for (int c = 0; c < 2; ++c) {
      for (int i = 0; i < 20; ++i) {
        Eigen::Vector2d uv;
        if (!f.cameras[c].Project((T_w_b * f.T_b_c[c]).inverse() * f.points[i],
                                  &uv)) {
          continue;
        }
        FeatureObservation o;
        o.feature_id = i;
        o.camera = c;
        o.uv = uv;
        frame.observations.push_back(o);
      }
    }
    f.frames.push_back(frame);
  }
  return f;
}

TEST(TrackTruth, ExactTracksHaveNoError) {
  const Fixture f = ExactTracks();
  const TrackTruthReport r = EvaluateTrackTruth(
      f.frames, f.cameras, f.T_b_c, f.poses, CastOnWall,
      [](const Eigen::Vector3d&, const Eigen::Vector3d&) { return true; });
  EXPECT_EQ(r.drift.count, 20u * 9u);
  EXPECT_EQ(r.step.count, 20u * 9u);
  EXPECT_EQ(r.stereo.count, 20u * 10u);
  EXPECT_LT(r.drift.max, 1e-6);
  EXPECT_LT(r.step.max, 1e-6);
  EXPECT_LT(r.stereo.max, 1e-6);
  EXPECT_EQ(r.hidden, 0);
  EXPECT_EQ(r.lengths.tracks, 20u);
  EXPECT_EQ(r.lengths.max, 10);
  EXPECT_DOUBLE_EQ(r.lengths.share[3], 1.0);  // all of 10-19 frames
  ASSERT_EQ(r.drift_by_age.size(), 3u);       // ages 1, 2, 5
  EXPECT_EQ(r.drift_by_age[2].first, 5);
}

TEST(TrackTruth, ReportsExactlyTheErrorPutIntoATrack) {
  const auto all_visible = [](const Eigen::Vector3d&, const Eigen::Vector3d&) {
    return true;
  };
  Fixture f = ExactTracks();
  // Feature 3 slides by (3, 4) px in cam0 from frame 6 on: drift 5 px in
  // frames 6-9 (4 samples), one step of 5 px at frame 6.
  for (int k = 6; k < 10; ++k) {
    for (FeatureObservation& o : f.frames[k].observations) {
      if (o.camera == 0 && o.feature_id == 3) o.uv += Eigen::Vector2d(3, 4);
    }
  }
  TrackTruthReport r = EvaluateTrackTruth(f.frames, f.cameras, f.T_b_c, f.poses,
                                          CastOnWall, all_visible);
  EXPECT_NEAR(r.drift.max, 5.0, 1e-6);
  EXPECT_NEAR(r.drift.share_over_3px * r.drift.count, 4.0, 1e-9);
  EXPECT_NEAR(r.step.max, 5.0, 1e-6);
  EXPECT_NEAR(r.step.share_over_3px * r.step.count, 1.0, 1e-9);
  // A stereo match is judged against its own frame's cam0 sighting.
  f = ExactTracks();
  for (FeatureObservation& o : f.frames[2].observations) {
    if (o.camera == 1 && o.feature_id == 7) o.uv.x() += 2.0;
  }
  r = EvaluateTrackTruth(f.frames, f.cameras, f.T_b_c, f.poses, CastOnWall,
                         all_visible);
  EXPECT_LT(r.drift.max, 1e-6);
  EXPECT_NEAR(r.stereo.max, 2.0, 1e-6);
  EXPECT_NEAR(r.stereo.share_over_1px * r.stereo.count, 1.0, 1e-9);
  EXPECT_NEAR(r.stereo.share_over_3px, 0.0, 1e-12);
}

TEST(TrackTruth, HiddenPointsAndFramesWithoutPoseAreCountedApart) {
  Fixture f = ExactTracks();
  f.poses.erase(f.poses.begin() + 4);  // frame 4 has no pose
  const TrackTruthReport r = EvaluateTrackTruth(f.frames, f.cameras, f.T_b_c,
                                                f.poses, CastOnWall, Visible);
  EXPECT_EQ(r.frames_without_pose, 1);
  // Points with y > 0.55 (features 16-19) are hidden from the cameras at
  // y < 0: cam1, 11 cm to the right of cam0, in frames 0-2.
  EXPECT_EQ(r.hidden, 4 * 3);
  EXPECT_EQ(r.stereo.count, 20u * 9u - 4u * 3u);
  EXPECT_LT(r.drift.max, 1e-6);
  EXPECT_LT(r.stereo.max, 1e-6);
  ExpectErrorContaining<std::invalid_argument>(
      [&] {
        EvaluateTrackTruth(f.frames, f.cameras, {f.T_b_c[0]}, f.poses,
                           CastOnWall, Visible);
      },
      "one extrinsic per camera");
}

TEST(EpipolarError, ExactTracksLieOnTheirLinesAndAnOffsetShowsItsNormalPart) {
  Fixture f = ExactTracks();
  const PoseAt pose_at = [&f](int64_t t_ns, Eigen::Isometry3d* T) {
    return InterpolatePose(f.poses, t_ns, T);
  };
  EpipolarReport r =
      EvaluateEpipolarError(f.frames, f.cameras[0], f.T_b_c[0], pose_at, 3);
  ASSERT_EQ(r.gaps.size(), 3u);
  for (const EpipolarGapStats& g : r.gaps) {
    EXPECT_EQ(g.error.count, 20u * (10u - g.gap));
    EXPECT_LT(g.error.max, 1e-6);
  }
  // Move feature 5 in frame 9 by 1 px perpendicular to its epipolar line
  // from frame 8 (in the undistorted image near the centre, where 1 px of
  // distorted image is about 1 px undistorted).
  const int id = 5;
  const Eigen::Isometry3d T_c8 = BodyAt(8) * f.T_b_c[0];
  const Eigen::Isometry3d T_c9 = BodyAt(9) * f.T_b_c[0];
  const Eigen::Isometry3d T_98 = T_c9.inverse() * T_c8;
  const Eigen::Vector3d t = T_98.translation();
  Eigen::Matrix3d t_x;
  t_x << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  const Eigen::Vector3d x8 = (T_c8.inverse() * f.points[id]).normalized();
  const Eigen::Vector3d l = t_x * T_98.linear() * x8;
  const Eigen::Vector2d normal = l.head<2>().normalized();
  for (FeatureObservation& o : f.frames[9].observations) {
    if (o.camera != 0 || o.feature_id != id) continue;
    // 1 px along the normal of the line in the undistorted image, taken
    // back to the distorted pixel.
    Eigen::Vector2d xy;
    ASSERT_TRUE(f.cameras[0].PixelToNormalized(o.uv, &xy));
    xy += normal / f.cameras[0].focal();
    o.uv = f.cameras[0].NormalizedToPixel(xy);
  }
  r = EvaluateEpipolarError(f.frames, f.cameras[0], f.T_b_c[0], pose_at, 1);
  EXPECT_NEAR(r.gaps[0].error.max, 1.0, 1e-6);
  EXPECT_EQ(r.pairs_without_baseline, 0);
}

TEST(PixelErrorStats, MedianPercentileAndShares) {
  const PixelErrorStats s = ComputePixelErrorStats(
      {0.5, 4.0, 0.1, 2.0, 0.3, 0.2, 0.4, 1.5, 0.6, 0.7});
  EXPECT_EQ(s.count, 10u);
  EXPECT_DOUBLE_EQ(s.median, 0.55);
  EXPECT_DOUBLE_EQ(s.p95, 4.0);  // the 10th of 10
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(s.share_over_1px, 0.3);
  EXPECT_DOUBLE_EQ(s.share_over_3px, 0.1);
  EXPECT_EQ(ComputePixelErrorStats({}).count, 0u);
}

TEST(PoseInterpolation, HalfWayIsHalfTheTranslationAndHalfTheAngle) {
  Trajectory t(2);
  t[0].t_ns = 100;
  t[1].t_ns = 300;
  t[1].p_w_b = Eigen::Vector3d(2, 0, 4);
  t[1].q_w_b =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitY()));
  Eigen::Isometry3d T;
  ASSERT_TRUE(InterpolatePose(t, 200, &T));
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(1, 0, 2), 1e-12));
  EXPECT_NEAR(Eigen::AngleAxisd(T.linear()).angle(), 0.4, 1e-12);
  EXPECT_FALSE(InterpolatePose(t, 99, &T));
  EXPECT_FALSE(InterpolatePose(t, 301, &T));
  ASSERT_TRUE(InterpolatePose(t, 300, &T));
  EXPECT_TRUE(T.translation().isApprox(t[1].p_w_b, 1e-12));
}

}  // namespace
}  // namespace vio
