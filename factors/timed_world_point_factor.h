#ifndef VIO_FACTORS_TIMED_WORLD_POINT_FACTOR_H_
#define VIO_FACTORS_TIMED_WORLD_POINT_FACTOR_H_

// Reprojection of a world point (WorldPointReprojectionFactor,
// factors/world_point_factor.h) with an online camera-IMU time offset t_d
// (t_imu = t_cam + t_d), as TimedReprojectionFactor does for the
// inverse-depth landmarks (factors/timed_reprojection_factor.h).
//
// Keyframe k's pose was placed at IMU time t_cam + t_d_k, t_d_k the offset
// estimate when the frame entered the window; the feature was really seen at
// t_cam + t_d, so at the pose's time it sits at
//   xy_k(t_d) = xy_k - (t_d - t_d_k) * v_k            (v_k: image velocity)
// and the residual is the world-point one on that shifted sighting:
//   p_c = T_b_c^-1 T_w_b^-1 p_w,
//   r   = sqrt_info * (p_c.xy / p_c.z - xy_k(t_d))    (2)
// Camera 1 of a keyframe saw the point at the same instant as camera 0: its
// sighting is shifted by the same t_d - t_d_k, along camera 1's own v_k.
//
// Jacobians:
//   pose, T_b_c, p_w: those of WorldPointReprojectionFactor (its header has
//     the derivation); the sighting enters r only as the additive -xy_k(t_d),
//     so they do not depend on the shift.
//   t_d: d xy_k(t_d) / d t_d = -v_k and r holds -xy_k(t_d), so
//     d r / d t_d = sqrt_info * v_k                   (2 x 1)
//   All four are zero when the point is behind (or at the centre of) the
//   camera where the Jacobians are taken, as in the other visual factors.
//
// First-estimate Jacobians (optional, p_w_first, keep_point_fej): the
// residual at p_w and the current t_d, the pose, T_b_c and p_w Jacobians at
// p_w_first as in WorldPointReprojectionFactor. The t_d Jacobian, sqrt_info
// v_k, depends on no block, so it is the same at the first estimate and at
// the current one; it is zeroed with the others (at p_w_first). v_k is a
// constant of the factor, given by its builder: the estimator predicts it
// from the frame's current state and the point's current p_w, not p_w_first
// (estimator/window_problem_points.cc), because it moves the residual, which
// is always taken at the current estimate; the two differ by a few per cent
// of depth, times a shift of a few ms.
//
// Parameter blocks, in this order:
//   pose   T_w_b (7) [t, q(x, y, z, w)]
//   T_b_c  the extrinsic of the camera that saw it (7)
//   p_w    the point in the world [m] (3)
//   t_d    time offset [s] (1)
// Evaluate never fails.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

#include "factors/tangent_jacobians.h"
#include "factors/timed_reprojection_factor.h"

namespace vio {

class TimedWorldPointReprojectionFactor final
    : public ceres::SizedCostFunction<2, 7, 7, 3, 1>,
      public TangentJacobians {
 public:
  enum Block { kPose = 0, kExtrinsic = 1, kPoint = 2, kTimeOffset = 3 };

  // obs: the sighting (normalised coordinates), its image velocity in the
  // camera that saw it and the t_d that placed its frame's pose;
  // sqrt_info = focal [px] / sigma [px]. p_w_first (not owned, 3 values,
  // must outlive the factor): where the Jacobians are taken; nullptr: at p_w.
  TimedWorldPointReprojectionFactor(const TimedObservation& obs,
                                    double sqrt_info,
                                    const double* p_w_first = nullptr);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  bool EvaluateTangent(double const* const* parameters, double* residuals,
                       double** jacobians) const override;

 private:
  bool Compute(double const* const* parameters, double* residuals,
               double** jacobians, bool tangent) const;

  TimedObservation obs_;
  double sqrt_info_;
  const double* p_w_first_;
};

}  // namespace vio

#endif  // VIO_FACTORS_TIMED_WORLD_POINT_FACTOR_H_
