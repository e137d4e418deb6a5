#include "eval/track_truth.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_map>

namespace vio {
namespace {

constexpr int kAges[] = {1, 2, 5, 10, 20, 40};

Eigen::Isometry3d PoseOf(const StampedPose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = p.q_w_b.normalized().toRotationMatrix();
  T.translation() = p.p_w_b;
  return T;
}

// The scene point seen at pixel uv of a camera at T_w_c.
bool Cast(const CameraModel& camera, const Eigen::Isometry3d& T_w_c,
          const Eigen::Vector2d& uv, const RayCast& cast,
          Eigen::Vector3d* X_w) {
  Eigen::Vector2d xy;
  if (!camera.PixelToNormalized(uv, &xy)) return false;
  return cast(T_w_c.translation(), T_w_c.linear() * xy.homogeneous(), X_w);
}

// Where X projects in a camera at T_w_c; false when hidden or out of view.
bool Reproject(const CameraModel& camera, const Eigen::Isometry3d& T_w_c,
               const Eigen::Vector3d& X_w, const VisibilityTest& visible,
               Eigen::Vector2d* uv) {
  if (!camera.Project(T_w_c.inverse() * X_w, uv) || !camera.InImage(*uv)) {
    return false;
  }
  return visible(T_w_c.translation(), X_w);
}

struct Track {
  Eigen::Vector3d anchor_w;  // cast from the first sighting
  bool anchored = false;
  Eigen::Vector2d last_uv;
  Eigen::Isometry3d last_T_w_c;
  int sightings = 0;
};

}  // namespace

TrackLengthStats ComputeTrackLengths(const std::vector<FeatureFrame>& frames) {
  std::map<int64_t, int> length;
  for (const FeatureFrame& f : frames) {
    for (const FeatureObservation& o : f.observations) {
      if (o.camera == 0) ++length[o.feature_id];
    }
  }
  TrackLengthStats s;
  s.tracks = length.size();
  if (length.empty()) return s;
  std::vector<int> l;
  for (const auto& [id, n] : length) l.push_back(n);
  std::sort(l.begin(), l.end());
  const size_t n = l.size();
  double sum = 0.0;
  constexpr int kEdges[TrackLengthStats::kBuckets] = {1, 2, 5, 10, 20, 50};
  for (const int v : l) {
    sum += v;
    int bucket = 0;
    while (bucket + 1 < TrackLengthStats::kBuckets && v >= kEdges[bucket + 1]) {
      ++bucket;
    }
    s.share[bucket] += 1.0 / n;
  }
  s.mean = sum / n;
  s.median = n % 2 == 1 ? l[n / 2] : 0.5 * (l[n / 2 - 1] + l[n / 2]);
  s.p90 = l[std::max<size_t>(static_cast<size_t>(std::ceil(0.9 * n)), 1) - 1];
  s.max = l.back();
  return s;
}

TrackTruthReport EvaluateTrackTruth(const std::vector<FeatureFrame>& frames,
                                    const std::vector<CameraModel>& cameras,
                                    const std::vector<Eigen::Isometry3d>& T_b_c,
                                    const Trajectory& frame_poses,
                                    const RayCast& cast,
                                    const VisibilityTest& visible) {
  if (cameras.empty() || cameras.size() != T_b_c.size()) {
    throw std::invalid_argument(
        "EvaluateTrackTruth: one extrinsic per camera, at least one camera");
  }
  std::unordered_map<int64_t, const StampedPose*> pose_at;
  for (const StampedPose& p : frame_poses) pose_at[p.t_ns] = &p;
  TrackTruthReport report;
  std::vector<double> drift, step, stereo;
  std::map<int, std::vector<double>> by_age;
  std::unordered_map<int64_t, Track> tracks;
  for (const FeatureFrame& frame : frames) {
    const auto pose = pose_at.find(frame.t_ns);
    if (pose == pose_at.end()) {
      ++report.frames_without_pose;
      continue;
    }
    const Eigen::Isometry3d T_w_b = PoseOf(*pose->second);
    const Eigen::Isometry3d T_w_c0 = T_w_b * T_b_c[0];
    std::unordered_map<int64_t, Eigen::Vector3d> cam0_points;
    for (const FeatureObservation& o : frame.observations) {
      if (o.camera != 0) continue;
      Track& t = tracks[o.feature_id];
      Eigen::Vector2d uv;
      if (t.sightings == 0) {
        t.anchored = Cast(cameras[0], T_w_c0, o.uv, cast, &t.anchor_w);
        if (!t.anchored) ++report.cast_missed;
      } else if (t.anchored) {
        if (Reproject(cameras[0], T_w_c0, t.anchor_w, visible, &uv)) {
          drift.push_back((o.uv - uv).norm());
          for (const int age : kAges) {
            if (t.sightings == age) by_age[age].push_back(drift.back());
          }
        } else {
          ++report.hidden;
        }
        Eigen::Vector3d previous_w;
        if (Cast(cameras[0], t.last_T_w_c, t.last_uv, cast, &previous_w) &&
            Reproject(cameras[0], T_w_c0, previous_w, visible, &uv)) {
          step.push_back((o.uv - uv).norm());
        }
      }
      ++t.sightings;
      t.last_uv = o.uv;
      t.last_T_w_c = T_w_c0;
      Eigen::Vector3d X_w;
      if (cameras.size() > 1 && Cast(cameras[0], T_w_c0, o.uv, cast, &X_w)) {
        cam0_points[o.feature_id] = X_w;
      }
    }
    for (const FeatureObservation& o : frame.observations) {
      if (o.camera <= 0 || o.camera >= static_cast<int>(cameras.size())) {
        continue;
      }
      const auto point = cam0_points.find(o.feature_id);
      if (point == cam0_points.end()) continue;
      Eigen::Vector2d uv;
      if (Reproject(cameras[o.camera], T_w_b * T_b_c[o.camera], point->second,
                    visible, &uv)) {
        stereo.push_back((o.uv - uv).norm());
      } else {
        ++report.hidden;
      }
    }
  }
  report.drift = ComputePixelErrorStats(drift);
  report.step = ComputePixelErrorStats(step);
  report.stereo = ComputePixelErrorStats(stereo);
  for (const auto& [age, errors] : by_age) {
    report.drift_by_age.emplace_back(age, ComputePixelErrorStats(errors));
  }
  report.lengths = ComputeTrackLengths(frames);
  return report;
}

}  // namespace vio
