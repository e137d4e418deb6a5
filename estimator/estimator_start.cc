// The estimator's start path after an initialiser has succeeded
// (estimator/initialization.h): the first window from its states, the joint
// visual-inertial bundle adjustment that refines them, and the
// re-initialisation after a failure reset while moving.
//
// Why a joint adjustment right after the alignment (rather than VINS-Mono's
// alignment alone or ORB-SLAM3's inertial-only MAP step): the linear
// alignment treats the up-to-scale positions of the structure from motion as
// exact, and their noise sits in the scale's own column (errors in
// variables), which biases the scale low; the accelerometer bias it ignores
// moves the scale too (visual_inertial_alignment_test.cc shows both). An
// inertial-only MAP step keeps the first flaw. The joint adjustment over the
// window's IMU and visual factors (the estimator's own factors, with the
// scale implicit in every position and depth) is the maximum-likelihood
// estimate the alignment approximates; docs/initialisation.md has the
// figures before and after it.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>

#include "estimator/estimator.h"
#include "estimator/gyro_aided_refinement_check.h"
#include "estimator/image_velocity.h"
#include "estimator/scale_uncertainty.h"
#include "estimator/state_prior.h"
#include "preintegration/imu_preintegration.h"

namespace vio {
namespace {

double PathLength(const Window& window) {
  double length = 0.0;
  for (size_t k = 1; k < window.frames.size(); ++k) {
    length +=
        (window.frames[k]->p_w_b_value() - window.frames[k - 1]->p_w_b_value())
            .norm();
  }
  return length;
}

InitialFrame StateOf(const WindowFrame& f) {
  InitialFrame s;
  s.t_ns = f.t_ns;
  s.t_imu_ns = f.t_imu_ns;
  s.p_w_b = f.p_w_b_value();
  s.q_w_b = Eigen::Quaterniond(f.pose.data() + kPoseQ).normalized();
  s.v_w = f.v_w_value();
  s.b_a = Eigen::Vector3d(f.speed_bias.data() + kSbBa);
  s.b_g = f.b_g_value();
  return s;
}

}  // namespace

std::string DescribeNoStart(const EstimatorSummary& s) {
  if (!s.init_attempts.empty()) return DescribeInitFailures(s.init_attempts);
  if (s.frames == 0) return "no frame was given";
  if (s.frames_without_imu + s.frames_out_of_order >= s.frames) {
    return "no frame was covered by the IMU (" +
           std::to_string(s.frames_without_imu) + " frames without IMU)";
  }
  return "no attempt was made";
}

bool Estimator::StartFromInitialWindow(const InitialWindow& start,
                                       bool restart) {
  if (start.frames.empty()) return false;
  StartRecord record;
  record.t_ns = start.frames.back().t_ns;
  record.method = start.method;
  record.restart = restart;
  record.diagnostics = start.diagnostics;
  record.diagnostics.initial_b_a = start.frames.back().b_a;
  record.diagnostics.initial_b_g = start.frames.back().b_g;
  if (start.frames.size() == 1) {
    // The static start: one frame, at rest.
    reuse_tracks_until_ns_ = INT64_MIN;
    const InitialFrame& s = start.frames.front();
    EstimatorOutput state;
    state.p_w_b = s.p_w_b;
    state.q_w_b = s.q_w_b;
    state.v_w = s.v_w;
    state.b_a = s.b_a;
    state.b_g = s.b_g;
    StartWindow(FeatureFrame{s.t_ns, s.observations}, s.t_imu_ns, state,
                options_.state_prior.velocity_still);
    // Still by the static start's own test (the detector agrees unless its
    // windows differ): the next frame's interval may be tied to this one.
    newest_still_ = StillNow(0.0);
    record.window.push_back(StateOf(*window_.frames.back()));
    summary_.starts.push_back(std::move(record));
    return true;
  }
  // The running window (a re-initialisation) is kept to fall back on.
  auto saved_frames = std::move(window_.frames);
  window_.frames.clear();
  FeatureManager saved_features = std::move(features_);
  auto saved_prior = std::move(prior_);
  const auto saved_prior_blocks = prior_blocks_;
  auto saved_extrinsic_prior = std::move(extrinsic_prior_);
  const auto saved_extrinsic_blocks = extrinsic_prior_blocks_;
  const int64_t saved_keyframe = last_keyframe_id_;
  const int64_t saved_reuse_until = reuse_tracks_until_ns_;
  // A start in motion's scale and biases are still being corrected: its
  // leaving landmarks are reused, not made world points, for a while
  // (landmarks.reuse_after_moving_start_s), from its own slide on.
  // (At most 1e9 s: the stamp plus the span stays within int64.)
  reuse_tracks_until_ns_ =
      record.t_ns +
      std::llround(1e9 * std::min(options_.landmarks.reuse_after_moving_start_s,
                                  1e9));
  const size_t n = start.frames.size();
  double value = 0.0, limit = 0.0;
  InitFailure reason = InitFailure::kImuUnavailable;
  if (BuildWindow(start, restart)) {
    const double path_before = PathLength(window_);
    reason = RefineStart(start.method, &record.diagnostics, &value, &limit);
    record.diagnostics.refined_path_m = PathLength(window_);
    record.diagnostics.refine_scale_change =
        path_before > 0.0 ? PathLength(window_) / path_before - 1.0 : 0.0;
  }
  if (reason != InitFailure::kNone) {
    window_.frames = std::move(saved_frames);
    features_ = std::move(saved_features);
    prior_ = std::move(saved_prior);
    prior_blocks_ = saved_prior_blocks;
    extrinsic_prior_ = std::move(saved_extrinsic_prior);
    extrinsic_prior_blocks_ = saved_extrinsic_blocks;
    last_keyframe_id_ = saved_keyframe;
    reuse_tracks_until_ns_ = saved_reuse_until;
    InitAttempt a;
    a.t_ns = record.t_ns;
    a.method = start.method;
    a.reason = reason;
    a.value = value;
    a.limit = limit;
    summary_.init_attempts.push_back(a);
    return false;
  }
  // Every frame of the first window is a keyframe; Slide counted the newest.
  summary_.keyframes += static_cast<int64_t>(n) - 1;
  newest_still_ = StillNow(window_.frames.back()->v_w_value().norm());
  for (const auto& f : window_.frames) record.window.push_back(StateOf(*f));
  realign_.Stop();
  if (start.method == InitMethod::kMono ||
      start.method == InitMethod::kGyroAided) {
    std::vector<BufferedFrame> frames;
    for (const InitialFrame& f : start.frames) {
      frames.push_back({f.t_ns, f.t_imu_ns, f.observations});
    }
    realign_.Begin(frames, record.t_ns);
  }
  summary_.starts.push_back(std::move(record));
  if (restart) ++summary_.reinitializations;
  return true;
}

bool Estimator::AppendInitialFrames(const std::vector<InitialFrame>& frames,
                                    const std::vector<ImuSample>& imu,
                                    Window* w, FeatureManager* features,
                                    int64_t* next_id, int64_t* skipped) const {
  for (const InitialFrame& s : frames) {
    auto f = std::make_unique<WindowFrame>();
    if (!w->frames.empty()) {
      const WindowFrame& prev = *w->frames.back();
      try {
        f->imu = std::make_unique<ImuPreintegration>(
            prev.t_imu_ns, s.t_imu_ns, imu,
            Eigen::Vector3d(prev.speed_bias.data() + kSbBa), prev.b_g_value(),
            noise_, preintegration_);
      } catch (const std::invalid_argument&) {
        return false;
      }
    }
    f->id = (*next_id)++;
    f->t_ns = s.t_ns;
    f->t_imu_ns = s.t_imu_ns;
    f->t_d_at_stamp = w->t_d;
    f->gyr_b = GyroscopeAt(imu, s.t_imu_ns);
    f->keyframe = true;
    f->p_w_b() = s.p_w_b;
    f->q_w_b() = s.q_w_b.normalized();
    f->v_w() = s.v_w;
    f->b_a() = s.b_a;
    f->b_g() = s.b_g;
    *skipped += features->AddFrame(f->id, s.observations).skipped;
    w->frames.push_back(std::move(f));
  }
  return true;
}

bool Estimator::BuildWindow(const InitialWindow& start, bool restart) {
  features_ = FeatureManager(window_.num_cameras);
  if (!AppendInitialFrames(start.frames, imu_, &window_, &features_,
                           &next_frame_id_, &summary_.observations_skipped)) {
    return false;
  }
  // The initialiser's points become inverse depths in their anchors; the
  // other landmarks are triangulated as usual.
  for (auto& [id, l] : features_.landmarks()) {
    const auto it = start.points_w.find(id);
    if (it == start.points_w.end() || !l.HasAnchor()) continue;
    const Sighting& a = l.anchor();
    const double z =
        (window_.T_w_c(a.frame_id, a.camera).inverse() * it->second).z();
    if (z >= options_.triangulation.min_depth_m &&
        z <= options_.triangulation.max_depth_m) {
      l.triangulated = true;
      l.inverse_depth = 1.0 / z;
      ++summary_.landmarks_triangulated;
    }
  }
  summary_.landmarks_triangulated +=
      features_.TriangulateNew(PoseFn(), options_.triangulation);
  // The gauge (position, yaw) held on one frame; roll, pitch and velocity
  // left loose so that the adjustment corrects the alignment's gravity and
  // scale; the biases keep state_prior's sigmas. A scale change moves every
  // frame but the held one, so a re-start holds its newest, the frame
  // SetGauge put at the running pose: held on the oldest (as before), a
  // +14 % scale change moved the newest, and so the trajectory, 0.86 m at
  // the re-start (test/reinitialization_test.cc). A first start's gauge is
  // arbitrary; it keeps the oldest.
  StatePriorOptions sigmas = options_.state_prior;
  sigmas.tilt_rad = options_.init.refine_tilt_rad;
  WindowFrame& held =
      restart ? *window_.frames.back() : *window_.frames.front();
  prior_ = MakeStatePrior(held.pose.data(), held.speed_bias.data(), sigmas,
                          options_.init.max_speed_m_s);
  prior_blocks_ = {held.pose.data(), held.speed_bias.data()};
  SetExtrinsicPrior();
  DropWorldPoints();
  last_keyframe_id_ = window_.frames.back()->id;
  return true;
}

InitFailure Estimator::RefineStart(InitMethod method,
                                   InitDiagnostics* diagnostics, double* value,
                                   double* limit) {
  int landmarks = 0;
  auto make_problem = [&]() {
    auto p =
        std::make_unique<WindowProblem>(&window_, &features_, ProblemSettings());
    p->AddPrior(prior_.get(), prior_blocks_);
    if (extrinsic_prior_) {
      p->AddPrior(extrinsic_prior_.get(), extrinsic_prior_blocks_);
    }
    if (!p->AddImuFactors()) p.reset();
    if (p) landmarks = p->AddVisualFactors();
    return p;
  };
  auto solve = [&](WindowProblem* p) {
    if (options_.init.refine_iterations <= 0) return;
    SolverOptions solver = options_.solver;
    solver.max_iterations = options_.init.refine_iterations;
    // A step starts from the prediction, near its minimum, and stops at a
    // 1e-3 relative cost change; this solve starts from the alignment, far
    // from it (the scale ~10 % off), and runs to Ceres' default 1e-6.
    solver.function_tolerance = std::min(solver.function_tolerance, 1e-6);
    p->Solve(solver);
  };
  std::unique_ptr<WindowProblem> problem = make_problem();
  if (!problem) return InitFailure::kRefinementFailed;
  const double path_before = PathLength(window_);
  // A start's landmarks include outlier sightings (a stereo start's also
  // mismatched pairs), which the robust kernel bounds but does not remove:
  // out with them (as a step's slide would), before the start is judged.
  // Not the static start's (its landmarks are triangulated by the window).
  const StereoInitOptions& stereo = options_.init.stereo;
  int rounds = 0;
  if (method == InitMethod::kStereo) {
    rounds = stereo.refine_outlier_rounds;
  } else if (method == InitMethod::kMono || method == InitMethod::kGyroAided) {
    rounds = options_.init.mono.refine_outlier_rounds;
  }
  // Removes what `outliers` lists and builds the problem again; false when
  // it cannot be built.
  auto remove = [&](const OutlierReport& outliers) {
    problem.reset();
    outliers.RemoveFrom(&features_);
    diagnostics->refine_outliers_removed +=
        static_cast<int>(outliers.landmarks.size() + outliers.behind.size() +
                         outliers.sightings.size());
    // Re-anchored landmarks lost their depth with their anchor's sighting.
    summary_.landmarks_triangulated +=
        features_.TriangulateNew(PoseFn(), options_.triangulation);
    problem = make_problem();
    return problem != nullptr;
  };
  // First the gross ones, at the alignment's state: solved with them in,
  // the window ran to several times its scale, and the rounds below, judging
  // every sighting against that state, then removed good ones with the bad.
  for (int pass = 0; pass < rounds && stereo.refine_prescreen_threshold_px > 0;
       ++pass) {
    const OutlierReport gross =
        problem->Outliers(stereo.refine_prescreen_threshold_px);
    if (gross.empty()) break;
    diagnostics->refine_prescreen_removed += static_cast<int>(
        gross.landmarks.size() + gross.behind.size() + gross.sightings.size());
    if (!remove(gross)) return InitFailure::kRefinementFailed;
  }
  solve(problem.get());
  for (int round = 0; round < rounds; ++round) {
    const OutlierReport outliers =
        problem->Outliers(stereo.refine_outlier_threshold_px);
    if (outliers.empty()) break;
    if (!remove(outliers)) return InitFailure::kRefinementFailed;
    solve(problem.get());
  }
  // The failure rules of a step, against the alignment's newest state.
  const WindowFrame& newest = *window_.frames.back();
  StepCheck check;
  check.landmarks_in_problem = landmarks;
  check.p_before = check.p_after = newest.p_w_b_value();
  check.q_before = check.q_after =
      Eigen::Quaterniond(newest.pose.data() + kPoseQ).normalized();
  check.v_after = newest.v_w_value();
  check.b_a = Eigen::Vector3d(newest.speed_bias.data() + kSbBa);
  check.b_g = newest.b_g_value();
  const Failure failure = DetectFailure(check, options_.failure);
  if (failure != Failure::kNone) {
    *value = static_cast<double>(failure);
    *limit = 0.0;
    return InitFailure::kRefinementFailed;
  }
  const double change =
      path_before > 0.0 ? PathLength(window_) / path_before - 1.0 : 0.0;
  if (!(std::abs(change) <= options_.init.max_refine_scale_change)) {
    *value = change;
    *limit = options_.init.max_refine_scale_change;
    return InitFailure::kRefinementScaleChange;
  }
  // How well the adjusted window determines its scale (the joint
  // adjustment's covariance; estimator/scale_uncertainty.h).
  std::vector<const double*> poses;
  for (const auto& f : window_.frames) poses.push_back(f->pose.data());
  diagnostics->refined_scale_sigma =
      RelativeSpreadSigma(problem->CeresProblem().get(), poses);
  // A stereo start's scale is the calibrated baseline's: where the path
  // defines a scale, the adjustment may move it only so far.
  InitDiagnostics adjusted = *diagnostics;
  adjusted.refined_path_m = PathLength(window_);
  if (method == InitMethod::kStereo && ScaleChangeDefined(adjusted) &&
      !(std::abs(change) <= options_.init.stereo.max_refine_scale_change)) {
    *value = change;
    *limit = options_.init.stereo.max_refine_scale_change;
    return InitFailure::kRefinementScaleChange;
  }
  // The gyroscope-aided start holds b_a at zero and its own covariance
  // leaves b_a out, so its scale sigma is no guard (measured 0.7-2 % against
  // errors of up to 73 %): the adjusted window's sigma takes its place, and the
  // adjustment may move the start's scale by at most so many of it (a
  // larger move says the scale rests on the accelerometer bias;
  // docs/initialisation.md has the trials).
  if (method == InitMethod::kGyroAided) {
    const InitFailure gyro = CheckGyroAidedRefinement(
        change, diagnostics->refined_scale_sigma, options_.init.mono, value,
        limit);
    if (gyro != InitFailure::kNone) return gyro;
  }
  const double max_sigma = options_.init.mono.max_refined_scale_uncertainty;
  // 1 or more: no wait (the default; docs/initialisation.md has why).
  if (method == InitMethod::kMono && diagnostics->long_window &&
      max_sigma < 1.0 &&
      !(diagnostics->refined_scale_sigma >= 0.0 &&
        diagnostics->refined_scale_sigma <= max_sigma)) {
    *value = diagnostics->refined_scale_sigma;
    *limit = max_sigma;
    return InitFailure::kScaleUncertain;
  }
  Slide(*problem);
  return InitFailure::kNone;
}

void Estimator::TryReinitialize(const FeatureFrame& frame, int64_t t_imu_ns,
                                EstimatorOutput* out) {
  init_.AddFrame(frame, t_imu_ns);
  InitialWindow start;
  if (!init_.TryInMotion(imu_, &summary_.init_attempts, &start)) return;
  // The running estimate fixes the gauge: the trajectory continues.
  SetGauge(out->p_w_b, out->q_w_b, &start);
  if (!StartFromInitialWindow(start, /*restart=*/true)) return;
  reinit_pending_ = false;
  init_.Clear();
  *out = OutputOf(*window_.frames.back(), frame.t_ns);
}

}  // namespace vio
