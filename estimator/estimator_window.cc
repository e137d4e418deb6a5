// The estimator's window once a frame is in it: the solve and its figures,
// the check of the step, the slide (outliers out, the oldest keyframe
// marginalised into the prior) and the newest pose's covariance.

#include <algorithm>
#include <chrono>
#include <utility>

#include "estimator/estimator.h"
#include "estimator/marginalization.h"
#include "estimator/pose_covariance.h"
#include "estimator/state_prior.h"
#include "estimator/thread_cpu_time.h"
#include "estimator/window_problem.h"

namespace vio {
namespace {

double Seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// The square root's path of one marginalisation, into the summary.
void CountSquareRoot(const MarginalizationResult& result,
                     EstimatorSummary* summary) {
  switch (result.square_root) {
    case PriorSquareRoot::kCholesky:
      ++summary->prior_cholesky;
      break;
    case PriorSquareRoot::kBlockFloor:
      ++summary->prior_block_floor;
      break;
    case PriorSquareRoot::kNullSpaceFloor:
      ++summary->prior_subspace_floor;
      break;
    case PriorSquareRoot::kEigen:
      ++summary->prior_eigen;
      break;
  }
}

}  // namespace

void Estimator::Solve(WindowProblem* problem) {
  summary_.landmarks_per_step.Add(problem->landmarks_used());
  summary_.window_frames_per_step.Add(
      static_cast<double>(window_.frames.size()));
  summary_.residuals_per_step.Add(problem->num_residuals());
  const double cpu_start = ThreadCpuSeconds();
  const ceres::Solver::Summary solve =
      problem->Solve(options_.solver, &solver_);
  summary_.solver_cpu_time_s.Add(ThreadCpuSeconds() - cpu_start);
  summary_.solver_time_s.Add(solve.total_time_in_seconds);
  summary_.solver_jacobian_time_s += solve.jacobian_evaluation_time_in_seconds;
  summary_.solver_residual_time_s += solve.residual_evaluation_time_in_seconds;
  summary_.solver_linear_time_s += solve.linear_solver_time_in_seconds;
  summary_.solver_preprocess_time_s += solve.preprocessor_time_in_seconds;
  summary_.solver_iterations += static_cast<int64_t>(solve.iterations.size());
  if (solve.termination_type == ceres::FAILURE) ++summary_.solver_failures;
}

Failure Estimator::CheckStep(const EstimatorOutput& predicted, int landmarks,
                             int64_t t_ns) const {
  const EstimatorOutput solved = OutputOf(*window_.frames.back(), t_ns);
  StepCheck check;
  // Landmarks are only demanded of a full window: a still start has none.
  const bool full = window_.NumKeyframes() >= options_.window_size;
  check.landmarks_in_problem =
      full ? landmarks : options_.failure.min_tracked_landmarks;
  check.p_before = predicted.p_w_b;
  check.q_before = predicted.q_w_b;
  check.p_after = solved.p_w_b;
  check.q_after = solved.q_w_b;
  check.v_after = solved.v_w;
  check.b_a = solved.b_a;
  check.b_g = solved.b_g;
  return DetectFailure(check, options_.failure);
}

void Estimator::Slide(const WindowProblem& problem) {
  const OutlierReport outliers =
      problem.Outliers(options_.landmarks.outlier_threshold_px);
  // The world points as solved, before any is capped, marginalised or
  // released below (those about to be removed as outliers keep their
  // earlier record). Read-only for the estimate.
  std::vector<int64_t> points;
  for (const auto& [id, l] : features_.landmarks()) {
    if (l.world_point && !outliers.Involves(id)) points.push_back(id);
  }
  landmark_map_.RecordWorldPoints(features_, PoseFn(), points);
  const WindowFrame& newest = *window_.frames.back();
  const bool marginalize =
      newest.keyframe && window_.NumKeyframes() > options_.window_size;
  if (newest.keyframe) {
    last_keyframe_id_ = newest.id;
    ++summary_.keyframes;
  }
  // The marginalisation evaluates the problem's factors: before any
  // landmark they refer to is removed.
  if (marginalize) MarginalizeOldest(problem, outliers);
  outliers.RemoveFrom(&features_);
  summary_.landmarks_behind_removed +=
      static_cast<int64_t>(outliers.behind.size());
  summary_.outlier_landmarks_removed +=
      static_cast<int64_t>(outliers.landmarks.size());
  summary_.outlier_sightings_removed +=
      static_cast<int64_t>(outliers.sightings.size());
  if (marginalize) {
    landmark_map_.RecordAnchoredIn(features_, window_.frames.front()->id,
                                   PoseFn());
    features_.RemoveFrame(window_.frames.front()->id, PoseFn());
    window_.frames.pop_front();
    window_.frames.front()->imu.reset();
  }
  ReleaseOrphanPoints();
  UpdateImuLinearization();
}

WindowProblemSettings Estimator::ProblemSettings() const {
  WindowProblemSettings s;
  for (int c = 0; c < window_.num_cameras; ++c) {
    s.focal_px[c] = cameras_[c].focal_px;
  }
  s.visual = visual_;
  s.gravity_magnitude = options_.gravity_magnitude;
  s.estimate_extrinsics = options_.estimate_extrinsics;
  s.estimate_time_offset = options_.estimate_time_offset;
  s.max_landmarks = options_.landmarks.max_landmarks;
  s.keep_points =
      options_.landmarks.reanchored_tracks != ReanchoredTracks::kReuse &&
      !InReuseAfterMovingStart();
  s.point_first_estimates = options_.landmarks.reanchored_tracks ==
                            ReanchoredTracks::kKeepPointFirstEstimate;
  s.points_in_max_landmarks = options_.landmarks.world_points_in_max_landmarks;
  s.max_points = options_.landmarks.max_world_points;
  return s;
}

bool Estimator::InReuseAfterMovingStart() const {
  if (window_.frames.empty() ||
      window_.frames.back()->t_ns >= reuse_tracks_until_ns_) {
    return false;
  }
  // Never back to reuse once the prior holds world points.
  for (const auto& [id, l] : features_.landmarks()) {
    if (l.world_point) return false;
  }
  return true;
}

void Estimator::MarginalizeOldest(const WindowProblem& problem,
                                  const OutlierReport& outliers) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = ThreadCpuSeconds();
  const MarginalizationProblem m = problem.OldestFrameMarginalization(outliers);
  MarginalizationResult result = Marginalize(m);
  ++summary_.marginalizations;
  if (result.ok()) {
    prior_blocks_ = result.kept_parameter_blocks;
    CountSquareRoot(result, &summary_);
    prior_ = std::move(result).MakePrior();  // result's matrices moved out
    // Every sighting of a capped point is in the prior now: its track, if
    // it goes on, starts again as a new landmark. (One converted in this
    // step was no world point when the map last recorded them.)
    landmark_map_.RecordWorldPoints(features_, PoseFn(),
                                    problem.capped_points());
    for (const int64_t id : problem.capped_points()) features_.Forget(id);
    summary_.points_capped +=
        static_cast<int64_t>(problem.capped_points().size());
    // The extrinsic and gap-bias priors were folded factors: now in prior_.
    extrinsic_prior_.reset();
    extrinsic_prior_blocks_.clear();
    gap_bias_prior_.reset();
    gap_bias_prior_blocks_.clear();
  } else {
    // No usable prior: a fresh one on the frame that becomes the oldest.
    ++summary_.marginalization_failures;
    if (std::count(gap_bias_prior_blocks_.begin(), gap_bias_prior_blocks_.end(),
                   window_.frames[0]->speed_bias.data()) != 0) {
      gap_bias_prior_.reset();
      gap_bias_prior_blocks_.clear();
    }
    WindowFrame& next = *window_.frames[1];
    prior_ = MakeStatePrior(next.pose.data(), next.speed_bias.data(),
                            options_.state_prior,
                            options_.state_prior.velocity_moving);
    prior_blocks_ = {next.pose.data(), next.speed_bias.data()};
    SetExtrinsicPrior();
    DropWorldPoints();
  }
  // The world points that stay: those the oldest frame takes with it
  // (their last sighting is there) are no longer in any problem.
  const int64_t oldest_id = window_.frames.front()->id;
  int64_t world_points = 0;
  for (const auto& [id, l] : features_.landmarks()) {
    if (l.world_point &&
        std::any_of(l.sightings.begin(), l.sightings.end(),
                    [oldest_id](const Sighting& s) {
                      return s.frame_id != oldest_id;
                    })) {
      ++world_points;
    }
  }
  summary_.most_world_points =
      std::max(summary_.most_world_points, world_points);
  summary_.marginalization_time_s.Add(
      Seconds(std::chrono::steady_clock::now() - start));
  summary_.marginalization_cpu_time_s.Add(ThreadCpuSeconds() - cpu_start);
}

bool Estimator::NewestPoseCovariance(Eigen::Matrix<double, 6, 6>* covariance) {
  if (!initialized_ || window_.frames.empty()) return false;
  WindowProblem problem(&window_, &features_, ProblemSettings());
  if (prior_) problem.AddPrior(prior_.get(), prior_blocks_);
  if (extrinsic_prior_) {
    problem.AddPrior(extrinsic_prior_.get(), extrinsic_prior_blocks_);
  }
  if (!problem.AddImuFactors()) return false;
  problem.AddVisualFactors();
  return PoseCovariance(problem.CeresProblem().get(),
                        window_.frames.back()->pose.data(), covariance);
}

void Estimator::UpdateImuLinearization() {
  auto& frames = window_.frames;
  for (size_t k = 1; k < frames.size(); ++k) {
    const WindowFrame& i = *frames[k - 1];
    if (!frames[k]->imu) continue;  // across an IMU gap
    frames[k]->imu->UpdateBiasEstimate(
        Eigen::Vector3d(i.speed_bias.data() + kSbBa),
        Eigen::Vector3d(i.speed_bias.data() + kSbBg));
  }
}

}  // namespace vio
