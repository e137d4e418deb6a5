#ifndef VIO_FACTORS_TIMED_REPROJECTION_FACTOR_H_
#define VIO_FACTORS_TIMED_REPROJECTION_FACTOR_H_

// Monocular reprojection with an online camera-IMU time offset t_d
// (t_imu = t_cam + t_d), as in VINS-Mono's ProjectionTdFactor.
//
// Each keyframe's pose was placed at IMU time t_cam + t_d_k, with t_d_k the
// offset estimate when the frame entered the window. The feature was really
// seen at t_cam + t_d, so at the pose's time it sits at
//   xy_k(t_d) = xy_k - (t_d - t_d_k) * v_k            (v_k: image velocity)
// and the residual is that of ReprojectionFactor on the shifted coordinates:
//   f_i = (xy_i(t_d), 1),  p_c_i = f_i / rho,
//   p_c_j = T_b_c^-1 T_w_bj^-1 T_w_bi T_b_c p_c_i,
//   r = sqrt_info * (p_c_j.xy / p_c_j.z - xy_j(t_d))          (2)
//
// Parameter blocks, in this order:
//   pose_i (7), pose_j (7), T_b_c (7)   as in ReprojectionFactor
//   rho  inverse depth in camera i [1/m] (1)
//   t_d  time offset [s] (1)
// Degenerate geometry behaves as in ReprojectionFactor (zero Jacobians,
// t_d's included, when the point is behind camera j). Evaluate never fails.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

#include "factors/tangent_jacobians.h"

namespace vio {

// One observation with what the time offset needs.
struct TimedObservation {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // normalised coordinates [-]
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // d xy / dt [1/s]
  double t_d_at_stamp = 0.0;  // t_d used to place this frame's pose [s]
};

class TimedReprojectionFactor final
    : public ceres::SizedCostFunction<2, 7, 7, 7, 1, 1>,
      public TangentJacobians {
 public:
  enum Block {
    kPoseI = 0,
    kPoseJ = 1,
    kExtrinsic = 2,
    kInverseDepth = 3,
    kTimeOffset = 4
  };

  // obs_i: the anchor observation (keyframe i); obs_j: keyframe j.
  // sqrt_info = focal [px] / sigma [px].
  TimedReprojectionFactor(const TimedObservation& obs_i,
                          const TimedObservation& obs_j, double sqrt_info);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  bool EvaluateTangent(double const* const* parameters, double* residuals,
                       double** jacobians) const override;

 private:
  // Evaluate (tangent false) or EvaluateTangent (tangent true).
  bool Compute(double const* const* parameters, double* residuals,
               double** jacobians, bool tangent) const;

  TimedObservation obs_i_;
  TimedObservation obs_j_;
  double sqrt_info_;
};

// The same for a stereo rig: the anchor in camera 0 of keyframe i, the target
// in camera 1 of keyframe j (StereoTwoFrameReprojectionFactor with both
// observations shifted to their poses' times):
//   f_i = (xy_i(t_d), 1),  p_c_i = f_i / rho,
//   p_c1_j = T_b_c1^-1 T_w_bj^-1 T_w_bi T_b_c0 p_c_i,
//   r = sqrt_info * (p_c1_j.xy / p_c1_j.z - xy_j(t_d))        (2)
// v_j is camera 1's image velocity. (Within one keyframe both cameras see
// the same instant, so StereoReprojectionFactor needs no shift.)
//
// Parameter blocks, in this order:
//   pose_i (7), pose_j (7), T_b_c0 (7), T_b_c1 (7), rho (1), t_d (1)
class TimedStereoTwoFrameReprojectionFactor final
    : public ceres::SizedCostFunction<2, 7, 7, 7, 7, 1, 1>,
      public TangentJacobians {
 public:
  enum Block {
    kPoseI = 0,
    kPoseJ = 1,
    kExtrinsic0 = 2,
    kExtrinsic1 = 3,
    kInverseDepth = 4,
    kTimeOffset = 5
  };

  // obs_i: camera 0 of keyframe i (the anchor); obs_j: camera 1 of keyframe
  // j. sqrt_info = focal [px] / sigma [px].
  TimedStereoTwoFrameReprojectionFactor(const TimedObservation& obs_i,
                                        const TimedObservation& obs_j,
                                        double sqrt_info);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  bool EvaluateTangent(double const* const* parameters, double* residuals,
                       double** jacobians) const override;

 private:
  // Evaluate (tangent false) or EvaluateTangent (tangent true).
  bool Compute(double const* const* parameters, double* residuals,
               double** jacobians, bool tangent) const;

  TimedObservation obs_i_;
  TimedObservation obs_j_;
  double sqrt_info_;
};

}  // namespace vio

#endif  // VIO_FACTORS_TIMED_REPROJECTION_FACTOR_H_
