#ifndef VIO_FACTORS_CHECK_VISUAL_SCENE_H_
#define VIO_FACTORS_CHECK_VISUAL_SCENE_H_

// Random but realistic states for the visual factors: keyframes a few metres
// apart, a stereo rig with EuRoC-like extrinsics (camera z along body z,
// 11 cm baseline) perturbed by a few degrees and centimetres, landmarks 1-20 m
// in front of the anchor camera, time offsets of a few ms and image
// velocities of a few tenths per second. Shared by the factor cases (the
// jacobian_check tool), the factor tests, the bundle test and the benchmark.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <random>

#include "factors/inverse_depth_chain.h"
#include "factors/timed_reprojection_factor.h"

namespace vio {

using Block7 = Eigen::Matrix<double, 7, 1>;

// Which geometry to draw.
enum class VisualGeometry {
  kRealistic,         // landmark 1-20 m in front of both cameras
  kFarPoint,          // rho in [1e-6, 1e-3] 1/m: nearly at infinity
  kNegativeDepth,     // rho in [-0.05, -1e-6] 1/m: beyond infinity
  kNearTargetCamera,  // landmark 5-20 cm in front of the target camera
  kMixed,             // one of the above; realistic half of the time
};

// Which observation the scene's target is.
enum class VisualTarget {
  kMonoOtherFrame,    // cam0 of keyframe j
  kStereoSameFrame,   // cam1 of keyframe i (pose_j is unused, equals pose_i)
  kStereoOtherFrame,  // cam1 of keyframe j
};

// One landmark, its anchor observation (cam0 of keyframe i) and one target
// observation. obs_j.xy is the true projection plus pixel noise; with `timed`
// both observations also carry image velocities and the time shift
// (xy stored = xy at the pose's time + (t_d - t_d_at_stamp) * velocity).
struct VisualScene {
  Block7 pose_i, pose_j;          // T_w_bi, T_w_bj [m, quaternion]
  Block7 extrinsic0, extrinsic1;  // T_b_c0, T_b_c1 [m, quaternion]
  double rho = 0.0;               // inverse depth in cam0 of keyframe i [1/m]
  double t_d = 0.0;               // time offset t_imu - t_cam [s]
  TimedObservation obs_i, obs_j;  // anchor and target observation
  double sqrt_info = 0.0;         // focal / sigma [-]
};

// Draws a scene. noise_px is the pixel noise of the target observation [px]
// (0: exact). Resamples internally until the target camera sees the point.
VisualScene SampleVisualScene(std::mt19937& rng, VisualGeometry geometry,
                              VisualTarget target, bool timed,
                              double noise_px = 1.0);

// The homogeneous point (rho * p) of the scene's landmark in its target
// camera, at the scene's t_d: h.xy / h.z is the noise-free target
// observation, h.z the projective depth.
Eigen::Vector3d TargetPoint(const VisualScene& scene, VisualTarget target);

// Conversions between a 7-block [t, q(x, y, z, w)] and an isometry.
Eigen::Isometry3d IsometryFromBlock(const Block7& x);
Block7 BlockFromIsometry(const Eigen::Isometry3d& T);

// The world pose of the scene's target camera, T_w_c (the anchor camera is
// T_w_bi T_b_c0), and a way to move it: in one keyframe by changing T_b_c1,
// else by changing pose_j.
Eigen::Isometry3d TargetCameraPose(const VisualScene& scene,
                                   VisualTarget target);
void SetTargetCameraPose(const Eigen::Isometry3d& T_w_c, VisualTarget target,
                         VisualScene* scene);

}  // namespace vio

#endif  // VIO_FACTORS_CHECK_VISUAL_SCENE_H_
