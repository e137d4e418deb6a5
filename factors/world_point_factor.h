#ifndef VIO_FACTORS_WORLD_POINT_FACTOR_H_
#define VIO_FACTORS_WORLD_POINT_FACTOR_H_

// Reprojection of a landmark held as a point in the world (3 coordinates)
// into one camera of one keyframe. Unlike the inverse-depth factors no
// sighting is an anchor taken as exact: every sighting, the first included,
// has its own residual. The estimator holds a landmark this way once its
// inverse-depth anchor has been marginalised and the point is kept in the
// prior (estimator.landmarks.reanchored_tracks: keep_point,
// docs/recorded_flights.md).
//
//   p_b = R_w_b^T (p_w - t_w_b)                point in the body
//   p_c = R_b_c^T (p_b - t_b_c)                point in the camera
//   r   = sqrt_info * (p_c.xy / p_c.z - xy)    (2), units of sigma
// with sqrt_info = focal / sigma_px.
//
// Jacobians (right perturbation of the rigid blocks, pose_manifold.h:
// t (+) dt = t + dt, R (+) dtheta = R Exp(dtheta)), derivation:
//   (R Exp(dtheta))^T v = Exp(-dtheta) R^T v = R^T v + [R^T v]x dtheta
//   (first order), so
//   d p_b / d dt_w_b     = -R_w_b^T
//   d p_b / d dtheta_w_b = [p_b]x
//   d p_c / d dt_b_c     = -R_b_c^T
//   d p_c / d dtheta_b_c = [p_c]x
//   d p_c / d p_w        = R_b_c^T R_w_b^T
//   d p_c / d [dt_w_b, dtheta_w_b] = R_b_c^T [-R_w_b^T, [p_b]x]
// and d r / d x = d_r_d_p (ProjectResidual, inverse_depth_chain.h: sqrt_info
// / z [1 0 -x/z; 0 1 -y/z]) * d p_c / d x. The rigid blocks' 2 x 6 tangent
// Jacobians are lifted to the ambient 2 x 7 by LiftPoseJacobian
// (EvaluateTangent leaves them in the tangent space).
//
// First-estimate Jacobians (optional, p_w_first): the residual is taken at
// p_w, the Jacobians at p_w_first (p_b, p_c and d_r_d_p computed from it),
// so that every factor on the point is linearised where the marginalisation
// prior holding it was (Huang et al., first-estimate Jacobians; a point
// re-linearised beside a prior fixed at its first estimate gives the prior
// spurious information along the unobservable yaw and position,
// docs/recorded_flights.md). Then the Jacobians are not those of the
// residual: tools/jacobian_check and the tests check the factor without it.
//
// Degenerate geometry as the inverse-depth factors: a point closer than
// kMinProjectiveDepth [m] in front of the camera, or behind it, gives a
// finite, clamped residual and zero Jacobians. Evaluate never fails.
//
// Parameter blocks, in this order:
//   pose   T_w_b (7) [t, q(x, y, z, w)]
//   T_b_c  the extrinsic of the camera that saw it (7)
//   p_w    the point in the world [m] (3)

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

#include "factors/tangent_jacobians.h"

namespace vio {

// The residual above of the sighting xy and, when jacobians is not null,
// the Jacobians of parameters[0..2] (pose, T_b_c, p_w) into jacobians[0..2]
// (each may be null), ambient or tangent (2 x 6 for the rigid blocks), at
// p_w_first when it is not null. Returns whether those Jacobians are active
// (the point in front of the camera where they are taken). The work of
// WorldPointReprojectionFactor, shared with TimedWorldPointReprojectionFactor
// (factors/timed_world_point_factor.h), which passes its shifted sighting.
bool WorldPointReprojection(double const* const* parameters,
                            const Eigen::Vector2d& xy, double sqrt_info,
                            const double* p_w_first, bool tangent,
                            double* residuals, double** jacobians);

class WorldPointReprojectionFactor final
    : public ceres::SizedCostFunction<2, 7, 7, 3>,
      public TangentJacobians {
 public:
  enum Block { kPose = 0, kExtrinsic = 1, kPoint = 2 };

  // xy: the undistorted normalised coordinate [-] of the sighting;
  // sqrt_info = focal [px] / sigma [px].
  // p_w_first (not owned, 3 values, must outlive the factor): where the
  // Jacobians are taken; nullptr: at p_w.
  WorldPointReprojectionFactor(const Eigen::Vector2d& xy, double sqrt_info,
                               const double* p_w_first = nullptr);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  bool EvaluateTangent(double const* const* parameters, double* residuals,
                       double** jacobians) const override;

 private:
  Eigen::Vector2d xy_;
  double sqrt_info_;
  const double* p_w_first_;
};

}  // namespace vio

#endif  // VIO_FACTORS_WORLD_POINT_FACTOR_H_
