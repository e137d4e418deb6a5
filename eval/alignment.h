#ifndef VIO_EVAL_ALIGNMENT_H_
#define VIO_EVAL_ALIGNMENT_H_

// Closed-form alignment of an estimated trajectory to ground truth from the
// associated positions (orientations are not used, as in evo and in
// rpg_trajectory_evaluation). The estimate lives in its own world frame E;
// the alignment maps it into the ground truth's world frame W:
//
//   p_w = scale * R_w_e * p_e + t_w_e,      q_w_b = q_w_e * q_e_b,
//
// chosen to minimise sum_i |p_w_i(gt) - (scale * R_w_e * p_e_i + t_w_e)|^2
// over the transforms allowed by the mode:
//   none    identity.
//   se3     rotation + translation (6 DoF): Umeyama 1991 without scale, which
//           is evo's `--align`.
//   sim3    rotation + translation + scale (7 DoF): Umeyama with scale, evo's
//           `--align --correct_scale`.
//   posyaw  translation + rotation about the gravity axis z (4 DoF): the
//           unobservable directions of visual-inertial odometry when gravity
//           is known. Never rotates about x or y. Derived in alignment.cc.
//           When the ground truth spans less than kPosYawMinSpread in x-y (a
//           vehicle standing still), positions cannot tell the yaw: it is
//           then the circular mean of the yaw of q_gt * q_est^-1 over the
//           associated poses (the only case that uses orientations).
//
// Reference: S. Umeyama, "Least-squares estimation of transformation
// parameters between two point patterns", IEEE PAMI 13(4), 1991, eqs. 34-43.

#include <Eigen/Core>
#include <cstddef>
#include <string>

#include "dataset/trajectory.h"

namespace vio {

enum class AlignmentMode { kNone, kSe3, kSim3, kPosYaw };

// "none", "se3", "sim3" or "posyaw"; throws std::invalid_argument otherwise.
AlignmentMode ParseAlignmentMode(const std::string& name);
const char* AlignmentModeName(AlignmentMode mode);

// The fewest associated poses a mode can be estimated from: 1 for none, 2 for
// posyaw, 3 (not collinear) for se3 and sim3.
size_t MinimumPoses(AlignmentMode mode);

// RMS distance [m] of the ground-truth positions from their mean in x-y below
// which posyaw takes its yaw from the orientations.
constexpr double kPosYawMinSpread = 0.05;

// A similarity from the estimate's world E to the ground truth's world W.
struct Alignment {
  AlignmentMode mode = AlignmentMode::kNone;
  // posyaw only: the yaw came from the orientations (see kPosYawMinSpread).
  bool yaw_from_orientations = false;
  Eigen::Matrix3d R_w_e = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_w_e = Eigen::Vector3d::Zero();  // [m]
  double scale = 1.0;                               // [-] 1 except for sim3

  // The pose of the body in W: positions scaled, rotated and shifted,
  // orientations rotated. Stamps are kept.
  StampedPose Apply(const StampedPose& pose_e) const;
  Trajectory Apply(const Trajectory& trajectory_e) const;
};

// Aligns `estimate` to `ground_truth`, which must be associated (equal sizes,
// element i with element i; std::invalid_argument otherwise). Throws EvalError
// when there are fewer than MinimumPoses(mode) poses or the positions are
// degenerate for the mode (collinear for se3/sim3; for posyaw a spread
// ground truth whose x-y cross-covariance vanishes), naming the mode and the
// count.
Alignment Align(const Trajectory& estimate, const Trajectory& ground_truth,
                AlignmentMode mode);

}  // namespace vio

#endif  // VIO_EVAL_ALIGNMENT_H_
