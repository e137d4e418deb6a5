#include "estimator/gyro_aided_initializer.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

#include "estimator/gyro_aided_attitudes.h"
#include "estimator/gyro_aided_parallax.h"
#include "estimator/gyro_aided_solver.h"
#include "estimator/gyro_bias_from_rotations.h"
#include "estimator/in_motion_start.h"
#include "estimator/visual_inertial_alignment.h"
#include "preintegration/gyro_rotation.h"

namespace vio {
namespace {

// A track is kept for the final fit with at least this share of
// gyro_min_parallax_px [-].
constexpr double kTrackParallaxShare = 0.5;

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  return v[mid];
}

// Camera-0 tracks over frames[first..last], sighting frames relative to
// `first`; only those seen in at least two frames.
std::vector<GyroAidedTrack> TracksOf(const std::vector<BufferedFrame>& frames,
                                     int first, int last) {
  std::map<int64_t, GyroAidedTrack> by_id;
  for (int k = first; k <= last; ++k) {
    for (const FeatureObservation& o : frames[k].observations) {
      if (o.camera != 0 || !o.xy.allFinite()) continue;
      GyroAidedTrack& t = by_id[o.feature_id];
      t.id = o.feature_id;
      // One sighting per frame (a duplicate id in a frame keeps the first).
      if (!t.sightings.empty() && t.sightings.back().frame == k - first) {
        continue;
      }
      t.sightings.push_back({k - first, o.xy});
    }
  }
  std::vector<GyroAidedTrack> tracks;
  for (auto& [id, t] : by_id) {
    if (t.sightings.size() >= 2) tracks.push_back(std::move(t));
  }
  return tracks;
}

// Relative std of the spread S = sqrt(1/n sum |p_k - c|^2) of the given
// frames' positions p_k = v_0 T_k + g T_k^2 / 2 + alpha_k(b_a), to first
// order from the covariance of (v_0, g, b_a): dS/dp_k = (p_k - c) / (n S),
// and dp_k/d(v_0, g, b_a) = [T_k I, T_k^2 / 2 I, J_k] (the centroid's own
// derivative sums to zero against the p_k - c; J_k = d alpha_k / d b_a is
// linear, so its columns are exact differences).
double RelativeSpreadSigma(const GyroAidedProblem& problem,
                           const GyroAidedSolution& solution,
                           const std::vector<int>& frames) {
  const int n = static_cast<int>(frames.size());
  std::vector<GyroAidedFrameState> s;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k : frames) {
    s.push_back(FrameState(problem, solution, k));
    c += s.back().p_v_b;
  }
  c /= n;
  double spread = 0.0;
  for (const GyroAidedFrameState& f : s) spread += (f.p_v_b - c).squaredNorm();
  spread = std::sqrt(spread / n);
  if (!(spread > 0.0)) return std::numeric_limits<double>::infinity();
  Eigen::Matrix<double, 1, 9> J = Eigen::Matrix<double, 1, 9>::Zero();
  for (int i = 0; i < n; ++i) {
    const GyroAidedFrameState& f = s[i];
    const Eigen::RowVector3d d = (f.p_v_b - c).transpose() / (n * spread);
    J.segment<3>(0) += d * f.t_s;
    J.segment<3>(3) += d * 0.5 * f.t_s * f.t_s;
    for (int j = 0; j < 3; ++j) {
      GyroAidedSolution unit = solution;
      unit.b_a += Eigen::Vector3d::Unit(j);
      J(6 + j) += d * (FrameState(problem, unit, frames[i]).p_v_b - f.p_v_b);
    }
  }
  const double var = (J * solution.covariance * J.transpose())(0, 0);
  return std::sqrt(std::max(0.0, var)) / spread;
}

}  // namespace

GyroAidedInitializer::GyroAidedInitializer(
    const EstimatorOptions& options, const Eigen::Isometry3d& T_b_c,
    double focal_px, const ImuNoise& noise,
    const PreintegrationOptions& preintegration)
    : options_(options),
      T_b_c_(T_b_c),
      focal_px_(focal_px),
      noise_(noise),
      preintegration_(preintegration) {}

InitAttempt GyroAidedInitializer::TryInitialize(
    const std::vector<BufferedFrame>& frames, const std::vector<ImuSample>& imu,
    InitialWindow* window) const {
  const MonoInitOptions& m = options_.init.mono;
  auto failed = [&](InitFailure reason, double value, double limit) {
    return RefusedAttempt(frames.empty() ? 0 : frames.back().t_ns,
                          InitMethod::kGyroAided, reason, value, limit);
  };
  // Every frame of the window constrains; the selected ones are handed over.
  const std::vector<int> all = SelectFrames(frames, m.window_s, INT_MAX);
  const std::vector<int> selected =
      SelectFrames(frames, m.window_s, m.max_frames);
  const double span = SpanSeconds(frames, all);
  if (selected.size() < 3 || span < m.min_span_s) {
    return failed(InitFailure::kTooFewFrames, span, m.min_span_s);
  }
  const int first = all.front(), last = all.back();
  GyroAidedProblem problem;
  problem.T_b_c = T_b_c_;
  problem.focal_px = focal_px_;
  // b_a held at zero (the joint adjustment estimates it): estimated here
  // with state_prior's 0.2 m/s^2, the fit was measured to wander (the bias
  // 0.2 rad/s off on the hand-held preset, docs/initialisation.md).
  problem.accel_bias_sigma = 0.0;
  // The cheap checks first (the selected intervals' excitation, the
  // tracks counted), then the IMU from the first frame to every frame of
  // the window (~40 preintegrations over up to 2 s each: measured ~30 ms a
  // frame, which a sequence that never starts paid at every frame).
  std::vector<ImuPreintegration> intervals;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  if (!PreintegrateSelected(frames, selected, imu, noise_, preintegration_,
                            &intervals)) {
    return failed(InitFailure::kImuUnavailable, 0.0, 0.0);
  }
  window->diagnostics = InitDiagnostics();
  const double excitation = ImuExcitation(intervals);
  window->diagnostics.imu_excitation = excitation;
  if (!(excitation >= m.min_imu_excitation)) {
    return failed(InitFailure::kLowImuExcitation, excitation,
                  m.min_imu_excitation);
  }
  problem.tracks = TracksOf(frames, first, last);
  const int min_tracks = m.gyro_min_tracks;
  if (static_cast<int>(problem.tracks.size()) < min_tracks) {
    return failed(InitFailure::kFewCorrespondences,
                  static_cast<double>(problem.tracks.size()), min_tracks);
  }
  // The bias from the rotations alone is cheap (no depths, no velocity);
  // the fit on the reprojection errors that follows is not (in the unit
  // tests ~2.5 s against ~0.1 s for all before it). A pure rotation is
  // refused here, on the parallax that bias leaves, so that a sequence that
  // never starts does not pay the fit at every frame (sim_rotation's 15 s
  // took 145 s with the fit at every frame, docs/initialisation.md). It
  // needs the attitudes alone: one rotation-only pass over the samples
  // (preintegration/gyro_rotation.h), not the ~40 full preintegrations from
  // the first frame the fit needs (~55 % of a refused attempt's time when
  // they were built first). The same attitudes up to rounding, so the same
  // verdict and, for an attempt that passes, the same start.
  std::vector<int64_t> t_imu_ns;
  for (int k = first + 1; k <= last; ++k) t_imu_ns.push_back(frames[k].t_imu_ns);
  std::vector<GyroRotation> rotations;
  try {
    rotations = IntegrateGyroRotations(frames[first].t_imu_ns, t_imu_ns, imu,
                                       zero, preintegration_.max_sample_gap);
  } catch (const std::invalid_argument&) {
    return failed(InitFailure::kImuUnavailable, 0.0, 0.0);
  }
  const GyroAidedAttitudes attitudes(std::move(rotations));
  Eigen::Vector3d b_g_rotations = zero;
  if (!FitGyroBiasFromRotations(attitudes, problem.tracks,
                                problem.T_b_c.linear(), &b_g_rotations)) {
    return failed(InitFailure::kScaleUncertain, 1.0, m.max_scale_uncertainty);
  }
  const double precheck_parallax =
      MedianRotationParallaxPx(problem, attitudes, b_g_rotations);
  window->diagnostics.parallax_px = precheck_parallax;
  if (!(precheck_parallax >= m.gyro_min_parallax_px)) {
    return failed(InitFailure::kLowParallax, precheck_parallax,
                  m.gyro_min_parallax_px);
  }
  try {
    for (int k = first + 1; k <= last; ++k) {
      problem.from_first.emplace_back(frames[first].t_imu_ns,
                                      frames[k].t_imu_ns, imu, zero, zero,
                                      noise_, preintegration_);
    }
  } catch (const std::invalid_argument&) {
    return failed(InitFailure::kImuUnavailable, 0.0, 0.0);
  }
  const double g = options_.gravity_magnitude;
  problem.gravity_magnitude = g;
  GyroAidedSolution solution;
  window->diagnostics.full_fit = true;
  // The fit starts from the bias fitted again to the full preintegrations'
  // attitudes (FitGyroAided's first step, a few ms): the rotation-only
  // Jacobian differs from theirs in the last bits, and the fit was measured
  // to carry such a difference into a different start (hand-held trial
  // 1008: 2.15 s and -19 % instead of 2.10 s and -1.5 %), so an attempt
  // that passes gives bit for bit the start it gave before the precheck.
  if (!FitGyroAided(&problem, zero, &solution)) {
    return failed(InitFailure::kScaleUncertain, 1.0, m.max_scale_uncertainty);
  }
  // A pure rotation leaves no parallax once the fitted rotation is out.
  std::vector<double> parallax;
  for (const GyroAidedTrack& t : problem.tracks) {
    parallax.push_back(TrackParallaxPx(problem, solution, t));
  }
  const double median_parallax = Median(parallax);
  window->diagnostics.parallax_px = median_parallax;
  if (!(median_parallax >= m.gyro_min_parallax_px)) {
    return failed(InitFailure::kLowParallax, median_parallax,
                  m.gyro_min_parallax_px);
  }
  // Tracks that do not fit (mismatches) are dropped once and the rest fitted
  // again from the bias found.
  // Tracks without parallax say nothing of the translation and their depth,
  // even its sign, is noise: they go too.
  std::vector<GyroAidedTrack> inliers;
  for (size_t t = 0; t < problem.tracks.size(); ++t) {
    if (solution.track_rms_px[t] <= m.pnp_threshold_px &&
        parallax[t] >= kTrackParallaxShare * m.gyro_min_parallax_px) {
      inliers.push_back(problem.tracks[t]);
    }
  }
  window->diagnostics.inliers = static_cast<int>(inliers.size());
  if (static_cast<int>(inliers.size()) < min_tracks) {
    return failed(InitFailure::kFewInliers, static_cast<double>(inliers.size()),
                  min_tracks);
  }
  if (inliers.size() < problem.tracks.size()) {
    problem.tracks = std::move(inliers);
    const Eigen::Vector3d b_g = solution.b_g;
    if (!FitGyroAided(&problem, b_g, &solution)) {
      return failed(InitFailure::kScaleUncertain, 1.0, m.max_scale_uncertainty);
    }
  }
  window->diagnostics.reprojection_rms_px = solution.rms_px;
  if (!(solution.rms_px <= m.max_reprojection_rms_px)) {
    return failed(InitFailure::kReprojectionError, solution.rms_px,
                  m.max_reprojection_rms_px);
  }
  // The mirror solution puts the points behind the cameras.
  const double median_depth = Median(solution.depth);
  if (!(median_depth > 0.0)) {
    return failed(InitFailure::kNegativeScale, median_depth, 0.0);
  }
  std::vector<int> handed;  // selected frames as problem frames
  for (int k : selected) handed.push_back(k - first);
  const double relative = RelativeSpreadSigma(problem, solution, handed);
  window->diagnostics.scale = 1.0;
  window->diagnostics.scale_uncertainty = relative;
  if (!(relative <= m.max_scale_uncertainty)) {
    return failed(InitFailure::kScaleUncertain, relative,
                  m.max_scale_uncertainty);
  }
  window->diagnostics.gravity_error = std::abs(solution.free_g_norm - g);
  if (!(window->diagnostics.gravity_error <= options_.init.max_gravity_error)) {
    return failed(InitFailure::kGravityMagnitude, solution.free_g_norm - g,
                  options_.init.max_gravity_error);
  }
  // The world: R_w_v takes gravity onto -z.
  const Eigen::Matrix3d R_w_v = GravityAlignedRotation(solution.g);
  window->frames.clear();
  double max_speed = 0.0;
  for (size_t i = 0; i < selected.size(); ++i) {
    const GyroAidedFrameState s = FrameState(problem, solution, handed[i]);
    const BufferedFrame& b = frames[selected[i]];
    InitialFrame f;
    f.t_ns = b.t_ns;
    f.t_imu_ns = b.t_imu_ns;
    f.p_w_b = R_w_v * s.p_v_b;
    f.q_w_b = Eigen::Quaterniond(R_w_v * s.R_v_b).normalized();
    f.v_w = R_w_v * s.v_v;
    f.b_a = solution.b_a;
    f.b_g = solution.b_g;
    f.observations = b.observations;
    max_speed = std::max(max_speed, s.v_v.norm());
    window->frames.push_back(std::move(f));
  }
  if (!(max_speed <= options_.init.max_speed_m_s)) {
    return failed(InitFailure::kImplausibleSpeed, max_speed,
                  options_.init.max_speed_m_s);
  }
  // Landmarks: the tracks with parallax, in front of their anchor.
  window->points_w.clear();
  for (size_t t = 0; t < problem.tracks.size(); ++t) {
    const GyroAidedTrack& track = problem.tracks[t];
    if (!(solution.depth[t] > 0.0) ||
        TrackParallaxPx(problem, solution, track) < m.gyro_min_parallax_px) {
      continue;
    }
    const GyroAidedSighting& a = track.sightings.front();
    const GyroAidedFrameState s = FrameState(problem, solution, a.frame);
    const Eigen::Vector3d p_v_c = s.p_v_b + s.R_v_b * T_b_c_.translation();
    const Eigen::Vector3d P =
        p_v_c + solution.depth[t] * s.R_v_b * T_b_c_.linear() *
                    Eigen::Vector3d(a.xy.x(), a.xy.y(), 1.0);
    window->points_w[track.id] = R_w_v * P;
  }
  window->method = InitMethod::kGyroAided;
  SetGauge(Eigen::Vector3d::Zero(), 0.0, window);
  InitAttempt ok;
  ok.t_ns = frames.back().t_ns;
  ok.method = InitMethod::kGyroAided;
  return ok;
}

}  // namespace vio
