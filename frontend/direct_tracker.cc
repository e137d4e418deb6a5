#include "frontend/direct_tracker.h"

#include <Eigen/Cholesky>
#include <stdexcept>
#include <utility>

namespace vio {
namespace {

// At most max_points of the points (0: all), evenly spread over the list.
std::vector<DepthPoint> Subsample(const std::vector<DepthPoint>& points,
                                  int max_points) {
  const size_t n = points.size();
  if (max_points <= 0 || n <= static_cast<size_t>(max_points)) return points;
  std::vector<DepthPoint> out;
  out.reserve(max_points);
  for (int k = 0; k < max_points; ++k) {
    out.push_back(points[k * n / max_points]);
  }
  return out;
}

}  // namespace

DirectTracker::DirectTracker(const DirectTrackerOptions& options)
    : options_(options) {
  std::string message;
  if (!options_.Validate(&message)) {
    throw std::invalid_argument("DirectTrackerOptions: " + message);
  }
}

bool DirectTracker::SolveNotesLm(const PhotometricAlignment& problem, int level,
                                 AlignmentState* state,
                                 std::vector<TrackIteration>* log) const {
  AlignmentLinearization lin = problem.Linearize(*state, true);
  log->push_back({level, 0, lin.error, 0.0, true, 0.0, lin.residuals});
  if (lin.residuals < options_.min_residuals) return false;
  const double floor = options_.lambda_floor;
  double lambda = 0.0;
  for (int i = 1; i <= options_.max_iterations; ++i) {
    bool level_done = false;
    while (true) {
      // (H + lambda diag(H)) step = -g, by Cholesky (the notes' G G^T).
      Eigen::MatrixXd A = lin.H;
      A.diagonal() *= 1.0 + lambda;
      const Eigen::LLT<Eigen::MatrixXd> llt(A);
      const Eigen::VectorXd step = llt.solve(-lin.g);
      if (llt.info() != Eigen::Success || !step.allFinite()) {
        return true;  // H is singular: nothing more to learn at this level
      }
      const AlignmentState candidate = problem.Plus(*state, step);
      AlignmentLinearization next = problem.Linearize(candidate, true);
      const bool better =
          next.residuals >= options_.min_residuals && next.error < lin.error;
      // The notes' small-step test, on the pose part of the step (the
      // brightness offset b is in grey levels and would dominate a norm).
      const double pose_step = step.head<6>().norm();
      log->push_back(
          {level, i, next.error, lambda, better, pose_step, next.residuals});
      const bool small_step = pose_step < options_.min_step;
      if (better) {
        *state = candidate;
        lin = std::move(next);
        lambda = lambda <= floor ? 0.0 : 0.5 * lambda;
        level_done = small_step;
        break;
      }
      if (small_step) {
        level_done = true;
        break;
      }
      lambda = lambda == 0.0 ? floor : 2.0 * lambda;
      if (lambda > options_.max_lambda) {
        level_done = true;
        break;
      }
    }
    if (level_done) break;
  }
  return true;
}

TrackResult DirectTracker::Track(const DirectKeyframe& keyframe,
                                 const ImagePyramid& left,
                                 const ImagePyramid* right,
                                 const Eigen::Isometry3d& T_r_l,
                                 const AlignmentState& initial) const {
  TrackResult result;
  result.state = initial;
  const int coarsest = options_.coarsest_level;
  if (coarsest >= keyframe.image.size() || coarsest >= left.size() ||
      (right != nullptr && coarsest >= right->size())) {
    result.failure = "the pyramids have fewer levels than coarsest_level";
    return result;
  }
  const bool stereo = right != nullptr && options_.stereo_weight > 0.0;
  for (int l = coarsest; l >= options_.finest_level; --l) {
    const std::vector<DepthPoint> points =
        Subsample(keyframe.points[l], options_.max_points);
    if (points.empty()) continue;
    std::vector<AlignmentTarget> targets = {
        {&left.level(l), Eigen::Isometry3d::Identity(), 1.0, 0}};
    if (stereo) {
      targets.push_back({&right->level(l), T_r_l, options_.stereo_weight, 1});
    }
    // A level averages 4^l pixels: its intensity noise is sigma_I / 2^l.
    DirectTrackerOptions level_options = options_;
    level_options.sigma_intensity = options_.sigma_intensity / (1 << l);
    const PhotometricAlignment problem(points, keyframe.image.level(l).camera,
                                       targets, level_options);
    const bool enough =
        options_.solver == DirectSolver::kNotesLm
            ? SolveNotesLm(problem, l, &result.state, &result.log)
            : SolveCeres(problem, l, &result.state, &result.log);
    if (l == options_.finest_level) {
      const AlignmentLinearization lin = problem.Linearize(result.state, false);
      result.error = lin.error;
      result.residuals = lin.residuals;
      result.overlap = problem.Overlap(result.state);
      result.ok = enough && lin.residuals >= options_.min_residuals;
      if (!result.ok) {
        result.failure = "too few residuals at the finest level (" +
                         std::to_string(lin.residuals) + ")";
      }
    }
  }
  if (!result.ok && result.failure.empty()) {
    result.failure = "the keyframe has no points at the finest level";
  }
  return result;
}

}  // namespace vio
