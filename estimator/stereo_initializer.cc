#include "estimator/stereo_initializer.h"

#include <map>

#include "estimator/in_motion_start.h"
#include "estimator/structure_from_motion.h"
#include "estimator/triangulation.h"

namespace vio {
namespace {

// Camera c's features of a frame, by feature id.
SfmFrame CameraFeatures(const BufferedFrame& frame, int camera) {
  SfmFrame f;
  for (const FeatureObservation& o : frame.observations) {
    if (o.camera == camera && o.xy.allFinite()) f.xy[o.feature_id] = o.xy;
  }
  return f;
}

// Triangulates the frame's stereo pairs (camera 0 at T_v_c0) and adds those
// not yet in *points_v; returns how many it added.
int AddStereoPoints(const BufferedFrame& frame, const Eigen::Isometry3d& T_v_c0,
                    const Eigen::Isometry3d& T_c0_c1,
                    const TriangulationOptions& options,
                    std::map<int64_t, Eigen::Vector3d>* points_v) {
  const SfmFrame left = CameraFeatures(frame, 0);
  const SfmFrame right = CameraFeatures(frame, 1);
  int added = 0;
  for (const auto& [id, xy0] : left.xy) {
    if (points_v->count(id) != 0) continue;
    const auto it = right.xy.find(id);
    if (it == right.xy.end()) continue;
    const std::vector<TriangulationView> views = {
        {Eigen::Isometry3d::Identity(), xy0}, {T_c0_c1, it->second}};
    Eigen::Vector3d p;
    double depth = 0.0;
    if (Triangulate(views, options, &p, &depth) == TriangulationStatus::kOk) {
      (*points_v)[id] = T_v_c0 * p;
      ++added;
    }
  }
  return added;
}

}  // namespace

StereoInitializer::StereoInitializer(
    const EstimatorOptions& options, const Eigen::Isometry3d& T_b_c0,
    const Eigen::Isometry3d& T_b_c1, double focal_px, const ImuNoise& noise,
    const PreintegrationOptions& preintegration)
    : options_(options),
      T_b_c0_(T_b_c0),
      T_c0_c1_(T_b_c0.inverse() * T_b_c1),
      focal_px_(focal_px),
      noise_(noise),
      preintegration_(preintegration) {}

InitAttempt StereoInitializer::TryInitialize(
    const std::vector<BufferedFrame>& frames, const std::vector<ImuSample>& imu,
    InitialWindow* window) const {
  const StereoInitOptions& s = options_.init.stereo;
  auto failed = [&](InitFailure reason, double value, double limit) {
    return RefusedAttempt(frames.empty() ? 0 : frames.back().t_ns,
                          InitMethod::kStereo, reason, value, limit);
  };
  const std::vector<int> selected =
      SelectFrames(frames, s.window_s, options_.window_size + 1);
  const double span = SpanSeconds(frames, selected);
  if (selected.size() < 3 || span < s.min_span_s) {
    return failed(InitFailure::kTooFewFrames, span, s.min_span_s);
  }
  std::vector<ImuPreintegration> intervals;
  if (!PreintegrateSelected(frames, selected, imu, noise_, preintegration_,
                            &intervals)) {
    return failed(InitFailure::kImuUnavailable, 0.0, 0.0);
  }
  window->diagnostics = InitDiagnostics();
  window->diagnostics.imu_excitation = ImuExcitation(intervals);
  // 1. Metric points from the oldest frame's pairs, in its camera 0 (= v).
  VisualTrajectory visual;
  visual.metric = true;
  AddStereoPoints(frames[selected.front()], Eigen::Isometry3d::Identity(),
                  T_c0_c1_, options_.triangulation, &visual.points_v);
  window->diagnostics.inliers = static_cast<int>(visual.points_v.size());
  if (static_cast<int>(visual.points_v.size()) < s.min_stereo_points) {
    return failed(InitFailure::kFewStereoPoints,
                  static_cast<double>(visual.points_v.size()),
                  s.min_stereo_points);
  }
  // 2. The later frames by PnP, each from the previous one's pose, on the
  // points of the frames before it: each placed frame adds the pairs of its
  // own not seen before. On the oldest frame's points alone the later
  // frames rest on fewer and fewer points, the far ones metres off in depth:
  // over a 0.45 s span their rotations disagreed with the gyroscope, or
  // their |g| with g, in 9 of 20 trials, against 6 with these points
  // (docs/initialisation.md, "Longer span, chained points, |g| in sigmas").
  SfmOptions pnp;
  pnp.focal_px = focal_px_;
  pnp.min_pnp_inliers = s.min_pnp_inliers;
  pnp.pnp_threshold_px = s.pnp_threshold_px;
  visual.T_v_c.assign(selected.size(), Eigen::Isometry3d::Identity());
  for (size_t k = 1; k < selected.size(); ++k) {
    int inliers = 0;
    // No guess: OpenCV's would fail on outlier sightings (PlaceCameraByPnp).
    if (!PlaceCameraByPnp(CameraFeatures(frames[selected[k]], 0),
                          visual.points_v, nullptr, pnp, &visual.T_v_c[k],
                          &inliers)) {
      return failed(InitFailure::kPnpFailed, inliers, s.min_pnp_inliers);
    }
    AddStereoPoints(frames[selected[k]], visual.T_v_c[k], T_c0_c1_,
                    options_.triangulation, &visual.points_v);
  }
  // 3. Gyroscope bias, velocities and gravity.
  InitAttempt a = AlignAndBuild(visual, frames, selected, T_b_c0_, options_,
                                &intervals, window);
  a.t_ns = frames.back().t_ns;
  a.method = InitMethod::kStereo;
  window->method = InitMethod::kStereo;
  return a;
}

}  // namespace vio
