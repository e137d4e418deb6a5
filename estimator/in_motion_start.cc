#include "estimator/in_motion_start.h"

#include <algorithm>
#include <cmath>

#include "estimator/visual_inertial_alignment.h"

namespace vio {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// The checks of a metric (stereo) trajectory guard against a failed PnP, not
// against the PnP's own errors, which the joint adjustment that completes the
// start removes with the gyroscope and every sighting. Its frames rest on
// stereo points whose depths are tens of centimetres uncertain at a few
// metres, so their rotations and positions err together; measured over 60
// trials of init_benchmark's motion_stereo at the 0.45 s span
// (docs/initialisation.md, "The 0.45 s stereo span"):
//   - the visual rotations' RMS misfit to the gyroscope: 0.14-0.53 deg on
//     trajectories the adjustment made good starts of (the one refused at
//     0.5 deg: tilt 0.83 deg, scale +0.4 %), 34.7 deg where PnP failed.
//     The limit for a metric trajectory is kMetricMisfitFactor times
//     init.max_rotation_misfit_deg.
//   - the free |g|'s distance from g in the linear solve's own sigma
//     (VelocityGravityScale::gravity_norm_sigma): median 0.9, p90 2.6 of
//     those sigmas, where a calibrated sigma gives 0.67 and 1.64; the sigma
//     is about kGravitySigmaUnderestimate too small (1.46 in the alignment's
//     own Monte Carlo test with independent noise,
//     GravityNormSigmaMatchesTheSpreadOfGravityNorm), and |g| is refused
//     beyond 3 calibrated sigmas (and beyond init.max_gravity_error).
constexpr double kMetricMisfitFactor = 2.0;
constexpr double kGravitySigmaUnderestimate = 1.5;
constexpr double kGravityNormSigmas = 3.0;

InitAttempt Failed(InitFailure reason, double value, double limit) {
  InitAttempt a;
  a.reason = reason;
  a.value = value;
  a.limit = limit;
  return a;
}

}  // namespace

std::vector<int> SelectFrames(const std::vector<BufferedFrame>& frames,
                              double window_s, int max_frames) {
  std::vector<int> in_window;
  if (frames.empty()) return in_window;
  const int64_t t_newest = frames.back().t_ns;
  const int64_t window_ns = std::llround(window_s * 1e9);
  for (int k = 0; k < static_cast<int>(frames.size()); ++k) {
    if (t_newest - frames[k].t_ns <= window_ns) in_window.push_back(k);
  }
  if (static_cast<int>(in_window.size()) <= max_frames) return in_window;
  // Evenly spread by index from the newest backwards, so that the newest
  // (the frame the start happens at) is kept and the spacing is regular.
  std::vector<int> selected;
  const double step = static_cast<double>(in_window.size() - 1) /
                      static_cast<double>(max_frames - 1);
  for (int i = max_frames - 1; i >= 0; --i) {
    const int back = static_cast<int>(std::lround(i * step));
    selected.push_back(in_window[in_window.size() - 1 - back]);
  }
  return selected;
}

double SpanSeconds(const std::vector<BufferedFrame>& frames,
                   const std::vector<int>& selected) {
  if (selected.size() < 2) return 0.0;
  return 1e-9 * static_cast<double>(frames[selected.back()].t_ns -
                                    frames[selected.front()].t_ns);
}

bool PreintegrateSelected(const std::vector<BufferedFrame>& frames,
                          const std::vector<int>& selected,
                          const std::vector<ImuSample>& imu,
                          const ImuNoise& noise,
                          const PreintegrationOptions& preintegration,
                          std::vector<ImuPreintegration>* intervals) {
  intervals->clear();
  try {
    for (size_t k = 0; k + 1 < selected.size(); ++k) {
      intervals->emplace_back(frames[selected[k]].t_imu_ns,
                              frames[selected[k + 1]].t_imu_ns, imu,
                              Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                              noise, preintegration);
    }
  } catch (const std::invalid_argument&) {
    intervals->clear();
    return false;
  }
  return true;
}

double ImuExcitation(const std::vector<ImuPreintegration>& intervals) {
  if (intervals.size() < 2) return 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const ImuPreintegration& i : intervals) {
    mean += i.delta().v / i.sum_dt();
  }
  mean /= static_cast<double>(intervals.size());
  double sum = 0.0;
  for (const ImuPreintegration& i : intervals) {
    sum += (i.delta().v / i.sum_dt() - mean).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(intervals.size() - 1));
}

InitAttempt AlignAndBuild(const VisualTrajectory& visual,
                          const std::vector<BufferedFrame>& frames,
                          const std::vector<int>& selected,
                          const Eigen::Isometry3d& T_b_c,
                          const EstimatorOptions& options,
                          std::vector<ImuPreintegration>* intervals,
                          InitialWindow* window) {
  const InitOptions& init = options.init;
  const int n = static_cast<int>(selected.size());
  // Body attitudes and camera positions in v: R_v_b = R_v_c R_c_b.
  std::vector<AlignmentFrame> aligned(n);
  for (int k = 0; k < n; ++k) {
    aligned[k].R_v_b = visual.T_v_c[k].linear() * T_b_c.linear().transpose();
    aligned[k].p_v_c = visual.T_v_c[k].translation();
  }
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const Eigen::Vector3d b_g = AlignGyroscopeBias(aligned, zero, intervals);
  const double misfit_deg = kRadToDeg * RotationMisfitRms(aligned, *intervals);
  const double misfit_limit =
      visual.metric ? kMetricMisfitFactor * init.max_rotation_misfit_deg
                    : init.max_rotation_misfit_deg;
  if (!(misfit_deg <= misfit_limit)) {
    return Failed(InitFailure::kRotationMismatch, misfit_deg, misfit_limit);
  }
  const bool estimate_scale = !visual.metric;
  AlignmentOptions alignment;
  alignment.estimate_scale = estimate_scale;
  // The accelerometer bias is held at zero here: on positions from the
  // structure from motion (millimetres of noise) estimating it soaks up the
  // noise (visual_inertial_alignment_test.cc); the joint adjustment
  // estimates it with the whole window.
  alignment.accel_bias_sigma = 0.0;
  VelocityGravityScale vgs;
  const Eigen::Vector3d t_b_c = T_b_c.translation();
  if (!SolveVelocityGravityScale(aligned, *intervals, t_b_c, zero, alignment,
                                 &vgs)) {
    return Failed(InitFailure::kScaleUncertain, 1.0,
                  init.mono.max_scale_uncertainty);
  }
  const double g = options.gravity_magnitude;
  window->diagnostics.gravity_error = std::abs(vgs.g_v.norm() - g);
  if (estimate_scale && !(vgs.scale > 0.0)) {
    return Failed(InitFailure::kNegativeScale, vgs.scale, 0.0);
  }
  if (estimate_scale) {
    const double relative = vgs.scale_sigma / vgs.scale;
    window->diagnostics.scale_uncertainty = relative;
    if (!(relative <= init.mono.max_scale_uncertainty)) {
      return Failed(InitFailure::kScaleUncertain, relative,
                    init.mono.max_scale_uncertainty);
    }
  }
  // Stereo: the PnP positions carry millimetres of noise, which over the
  // 0.45 s of the stereo start move the free |g| by up to 1.4 m/s^2 with the
  // trajectory sound (the joint adjustment then holds |g| at g); a |g| within
  // 3 of its calibrated sigmas (above) is that noise, not a wrong start.
  // Mono keeps the fixed limit: there |g| also checks the scale.
  const double gravity_limit =
      visual.metric ? std::max(init.max_gravity_error,
                               kGravityNormSigmas * kGravitySigmaUnderestimate *
                                   vgs.gravity_norm_sigma)
                    : init.max_gravity_error;
  if (!(window->diagnostics.gravity_error <= gravity_limit)) {
    return Failed(InitFailure::kGravityMagnitude, vgs.g_v.norm() - g,
                  gravity_limit);
  }
  if (!RefineGravity(aligned, *intervals, t_b_c, zero, g, alignment, &vgs) ||
      !(vgs.scale > 0.0)) {
    return Failed(InitFailure::kNegativeScale, vgs.scale, 0.0);
  }
  double max_speed = 0.0;
  for (const Eigen::Vector3d& v : vgs.v_v) {
    max_speed = std::max(max_speed, v.norm());
  }
  if (!(max_speed <= init.max_speed_m_s)) {
    return Failed(InitFailure::kImplausibleSpeed, max_speed,
                  init.max_speed_m_s);
  }
  // The world: R_w_v takes gravity onto -z; p_w_b = R_w_v (s pbar_c -
  // R_v_b t_b_c); points scale with s.
  const Eigen::Matrix3d R_w_v = GravityAlignedRotation(vgs.g_v);
  window->diagnostics.scale = vgs.scale;
  window->frames.clear();
  for (int k = 0; k < n; ++k) {
    const BufferedFrame& b = frames[selected[k]];
    InitialFrame f;
    f.t_ns = b.t_ns;
    f.t_imu_ns = b.t_imu_ns;
    f.p_w_b = R_w_v * (vgs.scale * aligned[k].p_v_c - aligned[k].R_v_b * t_b_c);
    f.q_w_b = Eigen::Quaterniond(R_w_v * aligned[k].R_v_b).normalized();
    f.v_w = R_w_v * vgs.v_v[k];
    f.b_a = vgs.b_a;
    f.b_g = b_g;
    f.observations = b.observations;
    window->frames.push_back(std::move(f));
  }
  window->points_w.clear();
  for (const auto& [id, p] : visual.points_v) {
    window->points_w[id] = R_w_v * (vgs.scale * p);
  }
  SetGauge(Eigen::Vector3d::Zero(), 0.0, window);
  return InitAttempt();
}

}  // namespace vio
