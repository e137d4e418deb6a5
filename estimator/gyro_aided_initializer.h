#ifndef VIO_ESTIMATOR_GYRO_AIDED_INITIALIZER_H_
#define VIO_ESTIMATOR_GYRO_AIDED_INITIALIZER_H_

// The gyroscope-aided monocular start in motion: the fallback of the
// structure-from-motion start (mono_initializer.h) when no frame pair shares
// enough features with enough parallax, which is the rule, not the
// exception, under fast rotation (a hand-held camera: features live ~0.6 s).
//
// With the frame attitudes taken from the gyroscope (preintegrated; its bias
// estimated below), every camera position and every landmark enter the
// bearing constraints linearly, so every short track of the window counts
// and no long-lived reference pair is needed (the rotation-translation
// decoupled closed form: Martinelli, "Closed-form solution of visual-inertial
// structure from motion", IJCV 2014; Kaiser, Martinelli, Fontana and
// Scaramuzza, "Simultaneous state initialization and gyroscope bias
// calibration in visual inertial aided navigation", RA-L 2017; He et al.,
// "Revisiting visual-inertial structure from motion for odometry and SLAM
// initialization", RA-L 2023).
//
// In the body frame v of the oldest frame (p_b0 = 0, R_0 = I), frame k at
// T_k seconds after it has, from the IMU preintegrated from frame 0
// (alpha_k, beta_k, R_k: position, velocity and rotation deltas),
//   p_bk = v_0 T_k + g T_k^2 / 2 + alpha_k,   v_k = v_0 + g T_k + beta_k,
// and camera 0 at p_ck = p_bk + R_k t_b_c with attitude R_ck = R_k R_b_c. A
// track first seen in frame f with normalised bearing u_f = (x, y, 1) is
// the point P = p_cf + lambda R_cf u_f (lambda: its depth there); each later
// sighting k with bearing (x_k, y_k, 1) says that the point projects there:
//   M_k R_ck^T (P - p_ck) = 0,   M_k = [[-1, 0, x_k], [0, -1, y_k]],
// two equations linear in x = (v_0, g) and lambda (b_a is held at zero
// here; the joint adjustment estimates it). Each track's depth is
// eliminated (Schur complement), leaving a small system for x, solved with
// |g| held at the configured g. That linear solution minimises an algebraic
// error, which on noisy data was measured biased (the scale -52 % with the
// true gyroscope bias and 1 px of feature noise), so it only starts a
// Gauss-Newton on the reprojection errors themselves (x and the depths;
// -0.4 % then). The gyroscope bias: first from the rotations alone (the
// smallest eigenvalue of the epipolar normals' scatter, Kneip and Lynen
// 2013: gyro_aided_solver.h), then by minimising the reprojection errors of
// that solution over the bias (variable projection, Gauss-Newton on its
// three components).
//
// Checks, each a refusal with its reason (init_attempt.h): the frames' span
// (mono.min_span_s), IMU excitation (mono.min_imu_excitation), tracks seen
// twice (mono.gyro_min_tracks: too few correspondences), their median
// rotation-compensated parallax (mono.gyro_min_parallax_px: a pure rotation
// leaves none; judged first at the bias fitted to the rotations alone, a
// cheap precheck before the costly fit, then at the fitted bias), tracks
// left after outliers are dropped (too few inliers),
// the reprojection RMS (mono.max_reprojection_rms_px), the landmarks in
// front (negative scale: the median depth), the relative std of the
// window's spread from the solution's covariance (mono.max_scale_uncertainty:
// scale not observable), |g| of the free solution (max_gravity_error) and
// the speeds (max_speed_m_s). The scale sigma leaves b_a out (held at
// zero), so it is small (0.7-2 % on the presets) and rarely refuses. The
// estimator's joint adjustment and its checks follow, as for every start,
// and two more that use the adjustment's covariance in its place
// (gyro_aided_refinement_check.h).

#include <Eigen/Geometry>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/init_attempt.h"
#include "estimator/initial_window.h"
#include "preintegration/imu_types.h"

namespace vio {

class GyroAidedInitializer {
 public:
  // T_b_c, focal_px: camera 0.
  GyroAidedInitializer(const EstimatorOptions& options,
                       const Eigen::Isometry3d& T_b_c, double focal_px,
                       const ImuNoise& noise,
                       const PreintegrationOptions& preintegration);

  // Tries to start at the newest of `frames` (oldest first) from every frame
  // of the last init.mono.window_s; the window handed over holds at most
  // init.mono.max_frames of them (in_motion_start.h, SelectFrames). On
  // success fills *window (method kGyroAided) and returns an attempt with
  // reason kNone; otherwise the reason, value and limit. Never throws on bad
  // data.
  InitAttempt TryInitialize(const std::vector<BufferedFrame>& frames,
                            const std::vector<ImuSample>& imu,
                            InitialWindow* window) const;

 private:
  EstimatorOptions options_;
  Eigen::Isometry3d T_b_c_;
  double focal_px_;
  ImuNoise noise_;
  PreintegrationOptions preintegration_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_GYRO_AIDED_INITIALIZER_H_
