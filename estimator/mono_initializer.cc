#include "estimator/mono_initializer.h"

#include <algorithm>

#include "estimator/in_motion_start.h"
#include "estimator/structure_from_motion.h"

namespace vio {
namespace {

SfmOptions SfmOptionsFrom(const EstimatorOptions& o, double focal_px) {
  const MonoInitOptions& m = o.init.mono;
  SfmOptions s;
  s.focal_px = focal_px;
  s.min_parallax_px = m.min_parallax_px;
  s.min_correspondences = m.min_correspondences;
  s.min_inliers = m.min_inliers;
  s.ransac_threshold_px = m.ransac_threshold_px;
  s.min_pnp_inliers = m.min_pnp_inliers;
  s.pnp_threshold_px = m.pnp_threshold_px;
  s.max_reprojection_rms_px = m.max_reprojection_rms_px;
  s.bundle_iterations = m.bundle_iterations;
  s.outlier_threshold_px = m.outlier_threshold_px;
  s.outlier_rounds = m.outlier_rounds;
  s.max_outlier_share = m.max_outlier_share;
  s.min_ray_angle_deg = o.triangulation.min_parallax_deg;
  return s;
}

// Camera-0 features of a frame, by feature id.
SfmFrame SfmFrameOf(const BufferedFrame& frame) {
  SfmFrame f;
  for (const FeatureObservation& o : frame.observations) {
    if (o.camera == 0 && o.xy.allFinite()) f.xy[o.feature_id] = o.xy;
  }
  return f;
}

}  // namespace

MonoInitializer::MonoInitializer(const EstimatorOptions& options,
                                 const Eigen::Isometry3d& T_b_c,
                                 double focal_px, const ImuNoise& noise,
                                 const PreintegrationOptions& preintegration)
    : options_(options),
      T_b_c_(T_b_c),
      focal_px_(focal_px),
      noise_(noise),
      preintegration_(preintegration) {}

InitAttempt MonoInitializer::TryInitialize(
    const std::vector<BufferedFrame>& frames, const std::vector<ImuSample>& imu,
    InitialWindow* window) const {
  const MonoInitOptions& m = options_.init.mono;
  const InitAttempt first = TryWindow(frames, imu, m.long_window_s, window);
  window->diagnostics.long_window = true;
  const bool sfm_failed = first.reason == InitFailure::kFewCorrespondences ||
                          first.reason == InitFailure::kLowParallax ||
                          first.reason == InitFailure::kFewInliers ||
                          first.reason == InitFailure::kPnpFailed ||
                          first.reason == InitFailure::kReprojectionError ||
                          first.reason == InitFailure::kTooManyOutliers ||
                          first.reason == InitFailure::kFewPointsLeft;
  const std::vector<int> all = SelectFrames(frames, m.long_window_s, 2);
  if (!sfm_failed || SpanSeconds(frames, all) <= m.window_s) return first;
  // The features did not last over the long window: the fallback window.
  const InitAttempt second = TryWindow(frames, imu, m.window_s, window);
  window->diagnostics.long_window = false;
  return second;
}

InitAttempt MonoInitializer::TryWindow(const std::vector<BufferedFrame>& frames,
                                       const std::vector<ImuSample>& imu,
                                       double window_s,
                                       InitialWindow* window) const {
  const MonoInitOptions& m = options_.init.mono;
  auto failed = [&](InitFailure reason, double value, double limit) {
    return RefusedAttempt(frames.empty() ? 0 : frames.back().t_ns,
                          InitMethod::kMono, reason, value, limit);
  };
  const std::vector<int> selected =
      SelectFrames(frames, window_s, m.max_frames);
  const double span = SpanSeconds(frames, selected);
  if (selected.size() < 3 || span < m.min_span_s) {
    return failed(InitFailure::kTooFewFrames, span, m.min_span_s);
  }
  std::vector<ImuPreintegration> intervals;
  if (!PreintegrateSelected(frames, selected, imu, noise_, preintegration_,
                            &intervals)) {
    return failed(InitFailure::kImuUnavailable, 0.0, 0.0);
  }
  const double excitation = ImuExcitation(intervals);
  window->diagnostics = InitDiagnostics();
  window->diagnostics.imu_excitation = excitation;
  if (!(excitation >= m.min_imu_excitation)) {
    return failed(InitFailure::kLowImuExcitation, excitation,
                  m.min_imu_excitation);
  }
  std::vector<SfmFrame> sfm_frames;
  for (int k : selected) sfm_frames.push_back(SfmFrameOf(frames[k]));
  const SfmResult sfm =
      SolveStructureFromMotion(sfm_frames, SfmOptionsFrom(options_, focal_px_));
  window->diagnostics.parallax_px = sfm.parallax_px;
  window->diagnostics.inliers = sfm.inliers;
  window->diagnostics.reprojection_rms_px = sfm.reprojection_rms_px;
  if (sfm.failure != InitFailure::kNone) {
    return failed(sfm.failure, sfm.value, sfm.limit);
  }
  window->diagnostics.sfm_outliers_removed = sfm.outlier_sightings;
  VisualTrajectory visual;
  visual.T_v_c = sfm.T_v_c;
  visual.points_v = sfm.points_v;
  visual.metric = false;
  // The sightings the SfM found to be outliers do not go on to the window
  // (its joint adjustment would have them, Huber-bounded, not removed).
  std::vector<BufferedFrame> cleaned;
  if (!sfm.removed.empty()) {
    cleaned = frames;
    for (const auto& [i, id] : sfm.removed) {
      std::vector<FeatureObservation>& obs = cleaned[selected[i]].observations;
      obs.erase(std::remove_if(obs.begin(), obs.end(),
                               [id = id](const FeatureObservation& o) {
                                 return o.camera == 0 && o.feature_id == id;
                               }),
                obs.end());
    }
  }
  InitAttempt a =
      AlignAndBuild(visual, sfm.removed.empty() ? frames : cleaned, selected,
                    T_b_c_, options_, &intervals, window);
  a.t_ns = frames.back().t_ns;
  a.method = InitMethod::kMono;
  window->method = InitMethod::kMono;
  return a;
}

}  // namespace vio
