#include "tools/track_report.h"

#include <cstdio>
#include <sstream>

#include "eval/pose_interpolation.h"
#include "render/scene_file.h"

namespace vio {
namespace {

std::vector<Eigen::Isometry3d> Extrinsics(const EurocSequence& sequence,
                                          size_t cameras) {
  std::vector<Eigen::Isometry3d> T_b_c;
  for (size_t c = 0; c < cameras; ++c) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = sequence.cameras[c].q_b_c.normalized().toRotationMatrix();
    T.translation() = sequence.cameras[c].t_b_c;
    T_b_c.push_back(T);
  }
  return T_b_c;
}

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0,
                   double d = 0.0) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), format, a, b, c, d);
  return buffer;
}

}  // namespace

TrackTruthReport TrackTruthOfRenderedSequence(
    const EurocSequence& sequence, const RenderTruth& truth,
    const std::vector<FeatureFrame>& frames) {
  std::vector<CameraModel> cameras;
  for (const CameraCalibration& c : sequence.cameras) cameras.emplace_back(c);
  const SceneGeometry& scene = truth.scene;
  const RayCast cast = [&scene](const Eigen::Vector3d& origin,
                                const Eigen::Vector3d& direction,
                                Eigen::Vector3d* point) {
    SceneHit hit;
    if (!scene.Intersect(origin, direction, &hit)) return false;
    *point = origin + hit.distance * direction.normalized();
    return true;
  };
  // A point on a surface is visible when nothing lies 1 mm before it.
  constexpr double kToleranceM = 1e-3;
  const VisibilityTest visible = [&scene](const Eigen::Vector3d& eye,
                                          const Eigen::Vector3d& point) {
    return scene.Visible(eye, point, kToleranceM);
  };
  return EvaluateTrackTruth(frames, cameras,
                            Extrinsics(sequence, cameras.size()),
                            truth.frame_poses, cast, visible);
}

EpipolarReport EpipolarErrorAgainst(const EurocSequence& sequence,
                                    const std::vector<FeatureFrame>& frames,
                                    const Trajectory& ground_truth,
                                    int max_gap) {
  const PoseAt pose_at = [&ground_truth](int64_t t_ns,
                                         Eigen::Isometry3d* T_w_b) {
    return InterpolatePose(ground_truth, t_ns, T_w_b);
  };
  return EvaluateEpipolarError(frames, CameraModel(sequence.cameras[0]),
                               Extrinsics(sequence, 1)[0], pose_at, max_gap);
}

std::string DescribePixelErrors(const PixelErrorStats& s) {
  std::ostringstream out;
  out << s.count << " samples";
  if (s.count == 0) return out.str();
  out << Format(": median %.3f px, p95 %.3f px, mean %.3f px, max %.1f px",
                s.median, s.p95, s.mean, s.max)
      << Format("; beyond 1 px %.2f %%, beyond 3 px %.2f %%",
                100.0 * s.share_over_1px, 100.0 * s.share_over_3px);
  return out.str();
}

std::string DescribeTrackLengths(const TrackLengthStats& s) {
  std::ostringstream out;
  out << "track lengths: " << s.tracks << " tracks"
      << Format(", mean %.1f, median %.1f, p90 %.0f frames, max ", s.mean,
                s.median, s.p90)
      << s.max << "\n  share of tracks by length: "
      << Format("1: %.1f %%, 2-4: %.1f %%, 5-9: %.1f %%, ", 100 * s.share[0],
                100 * s.share[1], 100 * s.share[2])
      << Format("10-19: %.1f %%, 20-49: %.1f %%, >= 50: %.1f %%\n",
                100 * s.share[3], 100 * s.share[4], 100 * s.share[5]);
  return out.str();
}

std::string DescribeTrackTruth(const TrackTruthReport& r) {
  std::ostringstream out;
  out << "frontend error against the rendered truth (mav0/render):\n"
      << "  drift, vs the track's first sighting  "
      << DescribePixelErrors(r.drift)
      << "\n  one step, vs the previous sighting     "
      << DescribePixelErrors(r.step)
      << "\n  stereo match, cam1 vs cam0             "
      << DescribePixelErrors(r.stereo) << "\n  drift by age:";
  for (const auto& [age, s] : r.drift_by_age) {
    out << Format(" %.0f: %.3f px (p95 %.2f);", age, s.median, s.p95);
  }
  out << "\n  not counted: " << r.hidden
      << " sightings of a point hidden or out of view, " << r.cast_missed
      << " first sightings whose ray met nothing, " << r.frames_without_pose
      << " frames without a pose\n"
      << DescribeTrackLengths(r.lengths);
  return out.str();
}

std::string DescribeEpipolarError(const EpipolarReport& r) {
  std::ostringstream out;
  out << "epipolar error of the cam0 tracks against the ground-truth poses:\n";
  for (const EpipolarGapStats& g : r.gaps) {
    out << "  " << g.gap << " frame(s) apart: " << DescribePixelErrors(g.error)
        << "\n";
  }
  out << "  not counted: " << r.frames_without_pose
      << " frames outside the ground truth, " << r.pairs_without_baseline
      << " frame pairs without baseline (< 1 mm)\n";
  return out.str();
}

}  // namespace vio
