#ifndef VIO_ESTIMATOR_GYRO_AIDED_SOLVER_H_
#define VIO_ESTIMATOR_GYRO_AIDED_SOLVER_H_

// The linear visual-inertial system of the gyroscope-aided start
// (gyro_aided_initializer.h has the equations and the references): with
// the frame attitudes from the gyroscope, the velocity of the first frame,
// gravity and every track's depth solve one linear least-squares problem;
// the gyroscope bias is fitted around it (FitGyroAided). Kept apart from the
// initialiser's checks so that the tests can hold it against exact data.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "preintegration/imu_preintegration.h"

namespace vio {

// One sighting of a track: the frame (index into the problem's frames) and
// the normalised image coordinates (x / z, y / z) in camera 0.
struct GyroAidedSighting {
  int frame = 0;
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
};

// A track: its sightings in increasing frame order, at most one per frame;
// the first is its anchor (the depth unknown lives there).
struct GyroAidedTrack {
  int64_t id = -1;
  std::vector<GyroAidedSighting> sightings;
};

struct GyroAidedProblem {
  // The IMU from frame 0 to frame k, for k = 1..n-1 (index k - 1),
  // linearised at b_a = 0 and any b_g.
  std::vector<ImuPreintegration> from_first;
  // The accelerometer bias is estimated with the prior N(0, sigma^2) per
  // axis [m/s^2]; 0 holds it at zero.
  double accel_bias_sigma = 0.2;
  // > 0: every solve holds |g| at this [m/s^2] (tangent-plane iterations
  // from the free solution); 0: g free.
  double gravity_magnitude = 0.0;
  Eigen::Isometry3d T_b_c = Eigen::Isometry3d::Identity();  // camera 0
  double focal_px = 460.0;  // weights the rows as pixels [px]
  std::vector<GyroAidedTrack> tracks;

  int NumFrames() const { return static_cast<int>(from_first.size()) + 1; }
};

// The solution, in the body frame v of frame 0 (p_b0 = 0, R_v_b0 = I).
struct GyroAidedSolution {
  Eigen::Vector3d v_0 = Eigen::Vector3d::Zero();  // velocity of frame 0 [m/s]
  Eigen::Vector3d g = Eigen::Vector3d::Zero();    // gravity in v [m/s^2]
  Eigen::Vector3d b_g = Eigen::Vector3d::Zero();  // gyroscope bias [rad/s]
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();  // accelerometer [m/s^2]
  std::vector<double> depth;  // per track, at its anchor [m]
  // Per track: RMS reprojection error of its non-anchor sightings [px]
  // (infinite when the point lies behind one of them).
  std::vector<double> track_rms_px;
  double rms_px = 0.0;       // over all non-anchor sightings [px]
  double free_g_norm = 0.0;  // |g| of the solve with g free [m/s^2]
  // Covariance of (v_0, g, b_a) from the normal equations scaled by the
  // residual's variance per row; with the magnitude of g fixed, of rank 8.
  Eigen::Matrix<double, 9, 9> covariance = Eigen::Matrix<double, 9, 9>::Zero();
};

// Frame k's state from a solution: body attitude, position and velocity in
// v, at the solution's biases (first-order corrected).
struct GyroAidedFrameState {
  Eigen::Matrix3d R_v_b = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_v_b = Eigen::Vector3d::Zero();  // [m]
  Eigen::Vector3d v_v = Eigen::Vector3d::Zero();    // [m/s]
  double t_s = 0.0;                                 // since frame 0 [s]
};
GyroAidedFrameState FrameState(const GyroAidedProblem& problem,
                               const GyroAidedSolution& solution, int k);

// Solves for v_0, g (|g| as problem.gravity_magnitude), b_a and the depths at
// the given gyroscope bias: the linear solution, its rows weighted by
// focal / depth with the depths of `previous` (else focal / 1 m), refined by
// Gauss-Newton on the reprojection errors. False with fewer than two tracks
// or a singular system.
bool SolveAtBias(const GyroAidedProblem& problem, const Eigen::Vector3d& b_g,
                 const GyroAidedSolution* previous, GyroAidedSolution* out);

// The full fit: the gyroscope bias from the rotations alone (Kneip and
// Lynen, ICCV 2013: the smallest eigenvalue of the scatter of the epipolar
// normals u_i x R_ij u_j of frame pairs 0.2 s apart vanishes at the right
// rotations, whatever the translation), then refined by Gauss-Newton on the
// reprojection errors of the solution at each bias (variable projection;
// `b_g_guess` is overridden by the first step only as its start), the IMU
// re-propagated at the bias (problem->from_first is updated), two passes.
// Each solution is the linear one refined by Gauss-Newton on the
// reprojection errors (x and depths). False when a solve fails.
bool FitGyroAided(GyroAidedProblem* problem, const Eigen::Vector3d& b_g_guess,
                  GyroAidedSolution* out);

}  // namespace vio

#endif  // VIO_ESTIMATOR_GYRO_AIDED_SOLVER_H_
