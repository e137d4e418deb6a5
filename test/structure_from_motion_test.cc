#include "estimator/structure_from_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <utility>

#include "dataset/simulator.h"
#include "frontend/observation_builder.h"

namespace vio {
namespace {

SimulatorOptions InMotion(double pixel_noise, uint32_t seed) {
  SimulatorOptions o;
  o.seed = seed;
  o.duration_s = 4.0;
  o.motion.still_duration_s = 0.0;
  o.motion.blend_duration_s = 0.0;
  o.motion.start_phase_s = 3.0;
  o.camera.pixel_noise_px = pixel_noise;
  o.imu.add_noise = false;
  return o;
}

Eigen::Isometry3d Cam0Extrinsic() {
  const CameraCalibration c = EurocCam0Calibration();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = c.q_b_c.toRotationMatrix();
  T.translation() = c.t_b_c;
  return T;
}

struct Case {
  std::vector<SfmFrame> frames;
  std::vector<Eigen::Isometry3d> T_w_c;  // truth
};

// `count` frames `stride` camera frames apart, ending at frame `last`.
Case MakeCase(const Simulation& sim, int last, int stride, int count) {
  ObservationBuilder builder({CameraModel(sim.options.camera.cam0)});
  Case c;
  for (int k = count - 1; k >= 0; --k) {
    FeatureFrame f = sim.frames[last - k * stride];
    builder.Process(&f);
    SfmFrame s;
    for (const FeatureObservation& o : f.observations) {
      if (o.camera == 0) s.xy[o.feature_id] = o.xy;
    }
    c.frames.push_back(s);
    for (const StampedState& gt : sim.ground_truth) {
      if (gt.t_ns == f.t_ns) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = gt.q_w_b.toRotationMatrix();
        T.translation() = gt.p_w_b;
        c.T_w_c.push_back(T * Cam0Extrinsic());
      }
    }
  }
  return c;
}

// Errors of the result against the truth, after the similarity that maps
// the result's reference camera and the newest's position onto the truth.
struct Errors {
  double position = 0.0;      // largest, relative to the path's extent [-]
  double rotation_deg = 0.0;  // largest relative-rotation error
};

Errors Compare(const SfmResult& r, const Case& c) {
  const int l = r.reference, n = static_cast<int>(c.frames.size()) - 1;
  // Relative rotations need no alignment.
  Errors e;
  for (int k = 0; k <= n; ++k) {
    const Eigen::Matrix3d est =
        r.T_v_c[l].linear().transpose() * r.T_v_c[k].linear();
    const Eigen::Matrix3d tru =
        c.T_w_c[l].linear().transpose() * c.T_w_c[k].linear();
    e.rotation_deg = std::max(
        e.rotation_deg,
        Eigen::AngleAxisd(est.transpose() * tru).angle() * 180.0 / M_PI);
  }
  // Positions in camera l's frame, scaled by the l -> n distance.
  const double s_est =
      (r.T_v_c[n].translation() - r.T_v_c[l].translation()).norm();
  const double s_tru =
      (c.T_w_c[n].translation() - c.T_w_c[l].translation()).norm();
  for (int k = 0; k <= n; ++k) {
    const Eigen::Vector3d est =
        r.T_v_c[l].inverse() * r.T_v_c[k].translation() / s_est;
    const Eigen::Vector3d tru =
        c.T_w_c[l].inverse() * c.T_w_c[k].translation() / s_tru;
    e.position = std::max(e.position, (est - tru).norm());
  }
  return e;
}

TEST(StructureFromMotion, NoiseFreeRecoversTheMotionUpToScale) {
  const Simulation sim = Simulate(InMotion(0.0, 1));
  const Case c = MakeCase(sim, 30, 3, 11);
  SfmOptions o;
  o.focal_px = 458.0;
  const SfmResult r = SolveStructureFromMotion(c.frames, o);
  ASSERT_EQ(r.failure, InitFailure::kNone)
      << InitFailureName(r.failure) << " " << r.value;
  const Errors e = Compare(r, c);
  std::printf(
      "noise-free: reference %d, parallax %.1f px, inliers %d, rms %.3f px, "
      "position %.2e, rotation %.2e deg\n",
      r.reference, r.parallax_px, r.inliers, r.reprojection_rms_px, e.position,
      e.rotation_deg);
  EXPECT_LT(e.position, 1e-4);
  EXPECT_LT(e.rotation_deg, 1e-3);
  EXPECT_LT(r.reprojection_rms_px, 1e-3);
}

// 1 px of feature noise, 11 frames 0.2 s apart, five seeds: the motion comes
// out within 3 % (of the reference pair's baseline) in position and 0.5 deg in
// relative rotation; the RMS is the noise of both ends of a residual
// (sqrt(2) px, the anchor bearing being held).
TEST(StructureFromMotion, WithPixelNoiseStaysCloseToTheTruth) {
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    const Simulation sim = Simulate(InMotion(1.0, seed));
    const Case c = MakeCase(sim, 40, 4, 11);
    SfmOptions o;
    o.focal_px = 458.0;
    o.ransac_threshold_px = 2.0;
    const SfmResult r = SolveStructureFromMotion(c.frames, o);
    ASSERT_EQ(r.failure, InitFailure::kNone)
        << InitFailureName(r.failure) << " " << r.value;
    const Errors e = Compare(r, c);
    std::printf(
        "1 px: reference %d, parallax %.1f px, inliers %d, rms %.3f px, "
        "position %.2e, rotation %.2e deg\n",
        r.reference, r.parallax_px, r.inliers, r.reprojection_rms_px,
        e.position, e.rotation_deg);
    // Measured 1.5-2.7 % and 0.15-0.35 deg.
    EXPECT_LT(e.position, 0.04) << seed;
    EXPECT_LT(e.rotation_deg, 0.5) << seed;
    EXPECT_LT(r.reprojection_rms_px, 1.7) << seed;
  }
}

// A camera turning about its IMU sees no parallax but its lever arm's: the
// rotation that best explains the matches leaves a pixel or so, and the start
// is refused for it, whatever the rotation's size.
TEST(StructureFromMotion, PureRotationIsRefusedForParallax) {
  SimulatorOptions o = InMotion(1.0, 3);
  o.motion.shape = SimShape::kRotation;
  const Simulation sim = Simulate(o);
  const Case c = MakeCase(sim, 40, 4, 11);
  SfmOptions options;
  options.focal_px = 458.0;
  const SfmResult r = SolveStructureFromMotion(c.frames, options);
  EXPECT_EQ(r.failure, InitFailure::kLowParallax) << InitFailureName(r.failure);
  EXPECT_LT(r.value, 10.0);
  EXPECT_EQ(r.limit, options.min_parallax_px);
  // The raw motion of the features is large: it is all rotation.
  double raw = 0.0;
  int n = 0;
  for (const auto& [id, xy] : c.frames.back().xy) {
    const auto it = c.frames.front().xy.find(id);
    if (it == c.frames.front().xy.end()) continue;
    raw += 458.0 * (xy - it->second).norm();
    ++n;
  }
  ASSERT_GT(n, 0);
  std::printf("pure rotation: raw parallax %.1f px, compensated %.1f px\n",
              raw / n, r.value);
  EXPECT_GT(raw / n, 3.0 * options.min_parallax_px);
}

TEST(StructureFromMotion, RotationCompensatedParallaxOfARotationIsZero) {
  std::vector<Eigen::Vector2d> a, b;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector2d x(0.02 * (i % 7) - 0.07, 0.015 * (i / 7) - 0.05);
    a.push_back(x);
    b.push_back((R * x.homogeneous()).hnormalized());
  }
  EXPECT_LT(RotationCompensatedParallax(a, b), 1e-12);
  // A translation along x shifts near points more than far ones: not a
  // rotation, so parallax remains.
  for (size_t i = 0; i < b.size(); ++i) {
    const double depth = 2.0 + (i % 5);
    b[i] = (Eigen::Vector3d(a[i].homogeneous()) * depth +
            Eigen::Vector3d(0.3, 0, 0))
               .hnormalized();
  }
  EXPECT_GT(RotationCompensatedParallax(a, b), 0.01);
}

// Points 2-8 m in front, 1 px of noise, and 15 % of the sightings gross
// outliers uniform over a 752 x 480 image, as camera.outlier_fraction makes
// them: the camera is placed within 0.5 deg and 5 cm, and the inliers it
// reports agree with the pose it returns. Placed with OpenCV's extrinsic
// guess (its final refinement then starts from RANSAC's last sample, not its
// best) and its inliers taken as reported, 3 of these 20 scenes came out
// 50-108 deg and 3.7-5.6 m off, none of the 108-119 inliers it reported
// agreeing with that pose (docs/initialisation.md, "The stereo start with
// outliers").
TEST(StructureFromMotion, PnpPlacesACameraAmongGrossOutliers) {
  const double f = 458.0;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 1.0 / f);
  for (int scene = 0; scene < 20; ++scene) {
    // The camera 0.3 m and a few degrees from the points' frame v.
    Eigen::Isometry3d T_v_c = Eigen::Isometry3d::Identity();
    T_v_c.linear() =
        Eigen::AngleAxisd(
            0.1 * (unit(rng) - 0.5),
            Eigen::Vector3d(unit(rng), unit(rng), 1.0).normalized())
            .matrix();
    T_v_c.translation() =
        0.3 * Eigen::Vector3d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng));
    std::map<int64_t, Eigen::Vector3d> points;
    SfmFrame frame;
    int outliers = 0;
    for (int64_t id = 0; id < 140; ++id) {
      const Eigen::Vector2d xy((unit(rng) - 0.5) * 752.0 / f,
                               (unit(rng) - 0.5) * 480.0 / f);
      const double depth = 2.0 + 6.0 * unit(rng);
      const Eigen::Vector3d p_c = depth * xy.homogeneous();
      points[id] = T_v_c * p_c;
      if (unit(rng) < 0.15) {
        frame.xy[id] = Eigen::Vector2d((unit(rng) - 0.5) * 752.0 / f,
                                       (unit(rng) - 0.5) * 480.0 / f);
        ++outliers;
      } else {
        frame.xy[id] = xy + Eigen::Vector2d(noise(rng), noise(rng));
      }
    }
    SfmOptions o;
    o.focal_px = f;
    Eigen::Isometry3d placed = Eigen::Isometry3d::Identity();
    int inliers = 0;
    ASSERT_TRUE(PlaceCameraByPnp(frame, points, nullptr, o, &placed, &inliers))
        << "scene " << scene << ", inliers " << inliers;
    const double rotation_deg =
        Eigen::AngleAxisd(placed.linear().transpose() * T_v_c.linear())
            .angle() *
        180.0 / M_PI;
    const double position_m =
        (placed.translation() - T_v_c.translation()).norm();
    int agreeing = 0;
    for (const auto& [id, xy] : frame.xy) {
      const Eigen::Vector3d p_c = placed.inverse() * points.at(id);
      if (p_c.z() > 0.0 &&
          f * (p_c.hnormalized() - xy).norm() <= o.pnp_threshold_px) {
        ++agreeing;
      }
    }
    EXPECT_LT(rotation_deg, 0.5) << "scene " << scene;
    EXPECT_LT(position_m, 0.05) << "scene " << scene;
    EXPECT_GE(agreeing, inliers) << "scene " << scene;
    EXPECT_GE(inliers, 140 - outliers - 10) << "scene " << scene;
  }
}

// The scene of WithPixelNoiseStaysCloseToTheTruth (1 px of noise, 11 frames
// 0.2 s apart) with 5 % of the sightings in the frames between the first and
// the newest replaced by hand with gross outliers, uniform over a 752 x 480
// image as camera.outlier_fraction makes them (at least 20 px off). Without
// the outlier rounds the bundle adjustment's RMS counts them and the
// reconstruction is refused; with its RMS check lifted it comes out far off.
// With the rounds, the gross outliers are removed (all but those a point's
// other sightings cannot tell: a point seen twice, or over a short baseline,
// fits one along its epipolar line), no sighting beyond the threshold is
// left, the RMS on the sightings kept is the clean scene's, and the motion is
// close to the truth. With a share limit below what was removed, the same
// scene is refused for it, with its own reason.
TEST(StructureFromMotion, GrossOutlierSightingsAreRemoved) {
  const double f = 458.0;
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    const Simulation sim = Simulate(InMotion(1.0, seed));
    Case c = MakeCase(sim, 40, 4, 11);
    std::mt19937 rng(100 + seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::set<std::pair<int, int64_t>> corrupted;
    const int n = static_cast<int>(c.frames.size());
    for (int k = 1; k + 1 < n; ++k) {
      for (auto& [id, xy] : c.frames[k].xy) {
        if (unit(rng) >= 0.05) continue;
        const Eigen::Vector2d bad((unit(rng) - 0.5) * 752.0 / f,
                                  (unit(rng) - 0.5) * 480.0 / f);
        if (f * (bad - xy).norm() < 20.0) continue;  // gross ones only
        xy = bad;
        corrupted.insert({k, id});
      }
    }
    ASSERT_GT(corrupted.size(), 40u);
    SfmOptions o;
    o.focal_px = f;
    o.ransac_threshold_px = 2.0;
    o.outlier_rounds = 0;
    const SfmResult without = SolveStructureFromMotion(c.frames, o);
    EXPECT_EQ(without.failure, InitFailure::kReprojectionError)
        << InitFailureName(without.failure) << " " << without.value;
    SfmOptions lifted = o;
    lifted.max_reprojection_rms_px = 1e9;
    const SfmResult kept_all = SolveStructureFromMotion(c.frames, lifted);
    ASSERT_EQ(kept_all.failure, InitFailure::kNone);
    const Errors e_all = Compare(kept_all, c);
    o.outlier_rounds = 3;
    const SfmResult r = SolveStructureFromMotion(c.frames, o);
    ASSERT_EQ(r.failure, InitFailure::kNone)
        << InitFailureName(r.failure) << " " << r.value;
    const std::set<std::pair<int, int64_t>> removed(r.removed.begin(),
                                                    r.removed.end());
    int left = 0;  // gross outliers left on the points kept
    for (const auto& [k, id] : corrupted) {
      if (r.points_v.count(id) > 0 && removed.count({k, id}) == 0) ++left;
    }
    for (int k = 0; k < n; ++k) {
      for (const auto& [id, xy] : c.frames[k].xy) {
        const auto p = r.points_v.find(id);
        if (p == r.points_v.end() || removed.count({k, id}) > 0) continue;
        const Eigen::Vector3d p_c = r.T_v_c[k].inverse() * p->second;
        EXPECT_LE(f * (p_c.hnormalized() - xy).norm(),
                  o.outlier_threshold_px)
            << "seed " << seed << ", frame " << k << ", feature " << id;
      }
    }
    const Errors e = Compare(r, c);
    std::printf(
        "seed %u: %zu gross outliers, %d left on kept points; RMS without "
        "the rounds %.1f px (lifted: position %.2e, rotation %.2f deg), with "
        "them %.3f px; removed %d of %d sightings (%.1f %%), position %.2e, "
        "rotation %.2f deg\n",
        seed, corrupted.size(), left, without.value, e_all.position,
        e_all.rotation_deg, r.reprojection_rms_px, r.outlier_sightings,
        r.sightings, 100.0 * r.outlier_share, e.position, e.rotation_deg);
    EXPECT_LE(left, static_cast<int>(corrupted.size()) / 10) << seed;
    EXPECT_LT(r.reprojection_rms_px, 1.7) << seed;
    EXPECT_LT(r.outlier_share, 0.15) << seed;
    // Measured 3.6-8.3 % and 0.57-1.11 deg; the outliers kept (Huber alone)
    // 8.5-19.7 % and 1.07-2.21 deg; the clean scene 1.6-2.3 % and
    // 0.24-0.36 deg, as with the gross outliers taken out by hand (so not
    // all the harm is undone: docs/initialisation.md).
    EXPECT_LT(e.position, 0.1) << seed;
    EXPECT_LT(e.rotation_deg, 1.5) << seed;
    EXPECT_LT(e.rotation_deg, e_all.rotation_deg * 1.1) << seed;
    o.max_outlier_share = 0.5 * r.outlier_share;
    const SfmResult refused = SolveStructureFromMotion(c.frames, o);
    EXPECT_EQ(refused.failure, InitFailure::kTooManyOutliers)
        << InitFailureName(refused.failure);
    EXPECT_EQ(refused.value, r.outlier_share);
  }
}

TEST(StructureFromMotion, TooFewFramesOrCorrespondencesFail) {
  SfmOptions o;
  EXPECT_EQ(SolveStructureFromMotion({SfmFrame()}, o).failure,
            InitFailure::kTooFewFrames);
  const SfmResult r = SolveStructureFromMotion({SfmFrame(), SfmFrame()}, o);
  EXPECT_EQ(r.failure, InitFailure::kFewCorrespondences);
  EXPECT_EQ(r.value, 0.0);
}

}  // namespace
}  // namespace vio
