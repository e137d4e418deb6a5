// The alternative solver of DirectTracker: the level's residuals as
// PhotometricFactors in a ceres::Problem, solved by Ceres'
// Levenberg-Marquardt.
//
// Parameterisation. The factor is written on world poses; here the host
// (keyframe) camera is the world: pose_i = identity (constant) and pose_j =
// T_h_t, the target's left camera in the host frame (= delta^-1), on
// PoseManifold. A target image k is reached through the constant extrinsic
// T_t_k = T_k_t^-1 (the right camera in the left camera's frame for the
// stereo term). Inverse depths and the host brightness are constant blocks;
// the target brightness pairs are free when estimate_affine.
//
// Weights. W_m (with lambda_k) is computed once, at the level's starting
// state, from PhotometricFactor::InverseDepthDerivative, and the Huber kernel
// is Ceres' HuberLoss on the weighted residual: the same cost as the notes'
// solver, except that W_m is frozen during the level.

#include <ceres/ceres.h>

#include <cmath>
#include <memory>
#include <vector>

#include "factors/photometric_factor.h"
#include "factors/pose_manifold.h"
#include "frontend/direct_tracker.h"

namespace vio {
namespace {

using Block7 = Eigen::Matrix<double, 7, 1>;  // [t, q(x, y, z, w)]

Rigid ToRigid(const Eigen::Isometry3d& T) {
  return {T.linear(), T.translation()};
}

Block7 ToBlock(const Eigen::Isometry3d& T) {
  Block7 x;
  x << T.translation(), Eigen::Quaterniond(T.linear()).normalized().coeffs();
  return x;
}

Eigen::Isometry3d FromBlock(const Block7& x) {
  const Rigid T = Rigid::FromBlock(x.data());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = T.R;
  out.translation() = T.t;
  return out;
}

}  // namespace

bool DirectTracker::SolveCeres(const PhotometricAlignment& problem, int level,
                               AlignmentState* state,
                               std::vector<TrackIteration>* log) const {
  Block7 pose_i = ToBlock(Eigen::Isometry3d::Identity());
  Block7 pose_j = ToBlock(state->T_t_h.inverse());
  double ab_host[2] = {0.0, 0.0};
  double ab[2][2] = {{state->affine[0][0], state->affine[0][1]},
                     {state->affine[1][0], state->affine[1][1]}};
  const std::vector<DepthPoint>& points = problem.points();
  std::vector<double> rho(points.size());
  for (size_t m = 0; m < points.size(); ++m) rho[m] = points[m].rho;

  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem ceres_problem(problem_options);
  const Rigid identity = ToRigid(Eigen::Isometry3d::Identity());
  int residuals = 0;
  for (size_t m = 0; m < points.size(); ++m) {
    const PhotometricHost host{points[m].uv, points[m].intensity,
                               problem.host_camera()};
    for (const AlignmentTarget& target : problem.targets()) {
      auto factor = std::make_unique<PhotometricFactor>(
          host, target.level->image, target.level->camera, identity,
          ToRigid(target.T_k_t.inverse()), 1.0);
      const double* params[] = {pose_i.data(), pose_j.data(), &rho[m], ab_host,
                                ab[target.affine]};
      double f = 0.0, d_f_d_rho = 0.0;
      if (!factor->InverseDepthDerivative(params, &f, &d_f_d_rho)) continue;
      const double W =
          target.weight *
          PhotometricWeight(problem.options().sigma_intensity,
                            options_.variance_weight ? d_f_d_rho : 0.0,
                            points[m].variance);
      factor->set_sqrt_weight(std::sqrt(W));
      ceres::LossFunction* loss =
          options_.huber_scale > 0.0
              ? new ceres::HuberLoss(options_.huber_scale)
              : nullptr;
      ceres_problem.AddResidualBlock(factor.release(), loss, pose_i.data(),
                                     pose_j.data(), &rho[m], ab_host,
                                     ab[target.affine]);
      ++residuals;
    }
  }
  if (residuals < options_.min_residuals) {
    log->push_back({level, 0, 0.0, 0.0, true, 0.0, residuals});
    return false;
  }
  ceres_problem.SetParameterBlockConstant(pose_i.data());
  ceres_problem.SetManifold(pose_j.data(), new PoseManifold);
  ceres_problem.SetParameterBlockConstant(ab_host);
  for (double& r : rho) {
    if (ceres_problem.HasParameterBlock(&r)) {
      ceres_problem.SetParameterBlockConstant(&r);
    }
  }
  for (int a = 0; a < 2; ++a) {
    if (ceres_problem.HasParameterBlock(ab[a]) && !options_.estimate_affine) {
      ceres_problem.SetParameterBlockConstant(ab[a]);
    }
  }
  ceres::Solver::Options solver;
  solver.minimizer_type = ceres::TRUST_REGION;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options_.max_iterations;
  solver.parameter_tolerance = options_.min_step;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &ceres_problem, &summary);
  // Ceres' cost is (1/2) sum rho_H(W f^2): twice it over the residual count
  // is the notes' mean error. Its LM damping is 1 / trust-region radius.
  for (const ceres::IterationSummary& it : summary.iterations) {
    log->push_back({level, it.iteration, 2.0 * it.cost / residuals,
                    it.iteration == 0 ? 0.0 : 1.0 / it.trust_region_radius,
                    it.step_is_successful, it.step_norm, residuals});
  }
  state->T_t_h = FromBlock(pose_j).inverse();
  for (int a = 0; a < 2; ++a) {
    state->affine[a] = Eigen::Vector2d(ab[a][0], ab[a][1]);
  }
  return true;
}

}  // namespace vio
