#include "estimator/visual_tracker.h"

#include <ceres/ceres.h>

#include <deque>
#include <memory>

#include "factors/pose_manifold.h"
#include "factors/reprojection_factor.h"
#include "factors/robust_kernel.h"
#include "factors/stereo_reprojection_factor.h"

namespace vio {
namespace {

// The constant blocks of the factors, copied so that the window is only
// read; a deque keeps their addresses.
struct Constants {
  std::array<std::array<double, 7>, kMaxCameras> extrinsics;
  std::deque<std::array<double, 7>> anchor_poses;
  std::deque<double> inverse_depths;
};

struct Term {
  std::unique_ptr<ceres::CostFunction> cost;
  std::vector<double*> blocks;
  bool inlier = true;
};

bool IsFinite(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

// One term per observation of a triangulated window landmark.
std::vector<Term> MakeTerms(const Window& window,
                            const FeatureManager& features,
                            const std::vector<FeatureObservation>& observations,
                            const VisualTrackerSettings& settings,
                            double* pose_j, Constants* constants) {
  std::vector<Term> terms;
  for (const FeatureObservation& o : observations) {
    if (o.camera < 0 || o.camera >= window.num_cameras) continue;
    const auto it = features.landmarks().find(o.feature_id);
    if (it == features.landmarks().end()) continue;
    const Landmark& l = it->second;
    if (!l.triangulated || !l.HasAnchor() || !o.xy.allFinite()) continue;
    const Sighting& a = l.anchor();
    const WindowFrame* frame_i = window.Find(a.frame_id);
    if (frame_i == nullptr) continue;
    constants->anchor_poses.push_back(frame_i->pose);
    constants->inverse_depths.push_back(l.inverse_depth);
    double* pose_i = constants->anchor_poses.back().data();
    double* rho = &constants->inverse_depths.back();
    double* ext0 = constants->extrinsics[0].data();
    const double sqrt_info =
        settings.visual.SqrtInformation(settings.focal_px[o.camera]);
    Term t;
    if (o.camera == 0) {
      t.cost = std::make_unique<ReprojectionFactor>(a.xy, o.xy, sqrt_info);
      t.blocks = {pose_i, pose_j, ext0, rho};
    } else {
      t.cost = std::make_unique<StereoTwoFrameReprojectionFactor>(a.xy, o.xy,
                                                                  sqrt_info);
      t.blocks = {pose_i, pose_j, ext0, constants->extrinsics[1].data(), rho};
    }
    terms.push_back(std::move(t));
  }
  return terms;
}

// Solves pose_j over the inlier terms; false when Ceres fails.
bool SolvePose(std::vector<Term>* terms, double* pose_j,
               const VisualTrackerSettings& settings) {
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  PoseManifold manifold;
  const std::unique_ptr<ceres::LossFunction> loss =
      MakeLossFunction(settings.visual.robust_kernel);
  problem.AddParameterBlock(pose_j, 7, &manifold);
  for (Term& t : *terms) {
    if (!t.inlier) continue;
    problem.AddResidualBlock(t.cost.get(), loss.get(), t.blocks);
    for (double* block : t.blocks) {
      if (block != pose_j) problem.SetParameterBlockConstant(block);
    }
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = settings.max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary.termination_type != ceres::FAILURE;
}

// Marks each term an inlier or not at the current pose; returns the count.
int ClassifyInliers(std::vector<Term>* terms,
                    const VisualTrackerSettings& settings) {
  // A whitened residual r = (focal / sigma) e is |r| sigma px.
  const double max_norm =
      settings.inlier_threshold_px / settings.visual.sigma_px;
  int inliers = 0;
  for (Term& t : *terms) {
    Eigen::Vector2d r;
    t.inlier = t.cost->Evaluate(t.blocks.data(), r.data(), nullptr) &&
               r.allFinite() && r.norm() <= max_norm;
    inliers += t.inlier ? 1 : 0;
  }
  return inliers;
}

}  // namespace

VisualPose TrackPoseOnLandmarks(
    const Window& window, const FeatureManager& features,
    const std::vector<FeatureObservation>& observations,
    const Eigen::Isometry3d& guess_T_w_b,
    const VisualTrackerSettings& settings) {
  VisualPose result;
  if (!IsFinite(guess_T_w_b)) return result;
  std::array<double, 7> pose_j = PoseArray(guess_T_w_b);
  Constants constants;
  constants.extrinsics = window.extrinsics;
  std::vector<Term> terms = MakeTerms(window, features, observations, settings,
                                      pose_j.data(), &constants);
  result.landmarks = static_cast<int>(terms.size());
  if (result.landmarks < settings.min_landmarks) return result;
  // Twice: over all terms under the robust kernel, then over the inliers
  // alone, so that the outliers' bounded pull is gone too.
  bool solved = SolvePose(&terms, pose_j.data(), settings);
  if (solved && ClassifyInliers(&terms, settings) >= settings.min_landmarks) {
    solved = SolvePose(&terms, pose_j.data(), settings);
  }
  result.inliers = ClassifyInliers(&terms, settings);
  const Eigen::Quaterniond q(pose_j.data() + kPoseQ);
  result.T_w_b.linear() = q.normalized().toRotationMatrix();
  result.T_w_b.translation() = Eigen::Vector3d(pose_j.data() + kPoseP);
  result.ok = solved && IsFinite(result.T_w_b) &&
              result.inliers >= settings.min_landmarks;
  return result;
}

}  // namespace vio
