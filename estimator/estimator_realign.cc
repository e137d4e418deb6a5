// The scale realignment after a monocular start in motion
// (estimator/scale_realignment.h): the longer span's start, adjusted jointly
// with the IMU like the start itself, against the running window; the window
// and its prior rescaled when they disagree (estimator/window_rescale.h).

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "estimator/estimator.h"
#include "estimator/image_velocity.h"
#include "estimator/scale_uncertainty.h"
#include "estimator/state_prior.h"
#include "estimator/window_problem.h"
#include "estimator/window_rescale.h"

namespace vio {

bool Estimator::AdjustSpan(InitialWindow* span) const {
  // A window of its own (the running one is not touched): the span's frames,
  // every one a keyframe, its points as inverse depths in their anchors.
  Window w;
  w.extrinsics = window_.extrinsics;
  w.num_cameras = window_.num_cameras;
  w.t_d = window_.t_d;
  FeatureManager features(window_.num_cameras);
  const std::vector<ImuSample>& imu = realign_.imu();
  int64_t id = 0;
  int64_t skipped = 0;  // counted once already, by the running estimator
  if (!AppendInitialFrames(span->frames, imu, &w, &features, &id, &skipped)) {
    return false;
  }
  const CameraPoseFn pose = [&w](int64_t frame, int camera) {
    return w.T_w_c(frame, camera);
  };
  for (auto& [fid, l] : features.landmarks()) {
    const auto it = span->points_w.find(fid);
    if (it == span->points_w.end() || !l.HasAnchor()) continue;
    const Sighting& a = l.anchor();
    const double z = (pose(a.frame_id, a.camera).inverse() * it->second).z();
    if (z >= options_.triangulation.min_depth_m &&
        z <= options_.triangulation.max_depth_m) {
      l.triangulated = true;
      l.inverse_depth = 1.0 / z;
    }
  }
  features.TriangulateNew(pose, options_.triangulation);
  // The start's gauge and loose tilt (BuildWindow), on the oldest frame.
  StatePriorOptions sigmas = options_.state_prior;
  sigmas.tilt_rad = options_.init.refine_tilt_rad;
  WindowFrame& held = *w.frames.front();
  const std::unique_ptr<MarginalizationPrior> prior =
      MakeStatePrior(held.pose.data(), held.speed_bias.data(), sigmas,
                     options_.init.max_speed_m_s);
  WindowProblemSettings settings = ProblemSettings();
  settings.estimate_extrinsics = false;
  settings.estimate_time_offset = false;
  settings.keep_points = false;
  settings.max_landmarks = std::max(settings.max_landmarks, 1);
  WindowProblem problem(&w, &features, settings);
  problem.AddPrior(prior.get(), {held.pose.data(), held.speed_bias.data()});
  if (!problem.AddImuFactors()) return false;
  problem.AddVisualFactors();
  SolverOptions solver = options_.solver;
  solver.max_iterations = std::max(options_.init.refine_iterations, 1);
  solver.function_tolerance = std::min(solver.function_tolerance, 1e-6);
  problem.Solve(solver);
  std::vector<const double*> poses;
  for (const auto& f : w.frames) poses.push_back(f->pose.data());
  span->diagnostics.refined_scale_sigma =
      RelativeSpreadSigma(problem.CeresProblem().get(), poses);
  for (size_t k = 0; k < span->frames.size(); ++k) {
    span->frames[k].p_w_b = w.frames[k]->p_w_b_value();
    span->frames[k].v_w = w.frames[k]->v_w_value();
    span->frames[k].q_w_b =
        Eigen::Quaterniond(w.frames[k]->pose.data() + kPoseQ).normalized();
    span->frames[k].b_a =
        Eigen::Vector3d(w.frames[k]->speed_bias.data() + kSbBa);
  }
  return true;
}

void Estimator::Realign(const FeatureFrame& frame, int64_t t_imu_ns) {
  if (!realign_.active()) return;
  realign_.AddFrame(frame, t_imu_ns);
  InitialWindow span;
  if (!realign_.TrySpan(frame.t_ns, &span)) return;
  if (!AdjustSpan(&span)) return;
  RealignmentResult r;
  if (!realign_.Compare(span, window_, &r)) return;
  RealignmentRecord record;
  record.t_ns = frame.t_ns;
  record.result = r;
  record.applied =
      std::abs(r.scale - 1.0) >= options_.init.mono.realign_min_change;
  if (record.applied) {
    // About the newest frame: its estimate does not jump. The span's
    // newest frame is this one: its tilt and accelerometer bias, which the
    // span determined together with its scale, go with the scale.
    WindowCorrection k;
    k.s = r.scale;
    k.c = window_.frames.back()->p_w_b_value();
    const InitialFrame& newest = span.frames.back();
    if (newest.t_ns == window_.frames.back()->t_ns) {
      const Eigen::Matrix3d R_w_b =
          Eigen::Quaterniond(window_.frames.back()->pose.data() + kPoseQ)
              .normalized()
              .toRotationMatrix();
      // After the rotation R the body must see the world's z where the
      // span's body sees it: (R R_w_b)^T z = R_s_b^T z, i.e. R^T z = u with
      // u = R_w_b R_s_b^T z; R is the smallest rotation taking u onto z
      // (a tilt: no yaw).
      const Eigen::Vector3d u = R_w_b * (newest.q_w_b.normalized().conjugate() *
                                         Eigen::Vector3d::UnitZ());
      k.R = Eigen::Quaterniond::FromTwoVectors(u, Eigen::Vector3d::UnitZ())
                .toRotationMatrix();
      k.delta_b_a = newest.b_a - window_.frames.back()->b_a();
    }
    if (prior_) {
      prior_ = CorrectPrior(*prior_, prior_blocks_, k, window_, features_);
    }
    if (gap_bias_prior_) {
      gap_bias_prior_ = CorrectPrior(*gap_bias_prior_, gap_bias_prior_blocks_,
                                     k, window_, features_);
    }
    CorrectWindow(k, &window_, &features_);
    UpdateImuLinearization();
  }
  summary_.realignments.push_back(record);
}

}  // namespace vio
