#include "frontend/direct_odometry.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace vio {
namespace {

Eigen::Isometry3d CameraPose(const CameraCalibration& c) {
  Eigen::Isometry3d T_b_c = Eigen::Isometry3d::Identity();
  T_b_c.linear() = c.q_b_c.normalized().toRotationMatrix();
  T_b_c.translation() = c.t_b_c;
  return T_b_c;
}

// The nearest rigid motion (rotation through a unit quaternion). Poses here
// are chained without end (T_w_c = T_w_kf delta^-1, the velocity, the
// prediction) and Isometry3d::inverse() transposes the rotation: a rotation
// that drifted off SO(3) would make every inverse wrong and the drift grow
// from frame to frame, geometrically through the velocity model.
Eigen::Isometry3d Rigid(const Eigen::Isometry3d& T) {
  Eigen::Isometry3d out = T;
  out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  return out;
}

const DirectOdometryOptions& Checked(const DirectOdometryOptions& options) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("DirectOdometryOptions: " + message);
  }
  return options;
}

}  // namespace

DirectOdometry::DirectOdometry(const CameraCalibration& left,
                               const CameraCalibration& right,
                               const DirectOdometryOptions& options)
    : options_(Checked(options)),
      left_undistorter_(left),
      right_undistorter_(right),
      T_r_l_(CameraPose(right).inverse() * CameraPose(left)),
      tracker_(options.tracker) {
  affine_[0] = affine_[1] = Eigen::Vector2d::Zero();
}

std::unique_ptr<DirectKeyframe> DirectOdometry::MakeKeyframe(
    int64_t t_ns, const ImagePyramid& left, const ImagePyramid& right,
    const Eigen::Isometry3d& T_w_c, StereoDepthStats* stats) const {
  const int level = options_.depth.level;
  std::vector<DepthPoint> points =
      StereoInverseDepth(left.level(level), right.level(level), T_r_l_, level,
                         options_.depth, stats);
  if (static_cast<int>(points.size()) < options_.min_keyframe_points) {
    return nullptr;
  }
  auto kf = std::make_unique<DirectKeyframe>(
      MakeDirectKeyframe(t_ns, left, std::move(points), level));
  kf->T_w_c = T_w_c;
  return kf;
}

DirectFrame DirectOdometry::Process(int64_t t_ns, const cv::Mat& left_raw,
                                    const cv::Mat& right_raw) {
  const int levels = options_.pyramid_levels;
  const ImagePyramid left(left_undistorter_.Undistort(left_raw),
                          left_undistorter_.pinhole(), levels);
  const bool stereo = !right_raw.empty();
  ImagePyramid right;
  if (stereo) {
    right = ImagePyramid(right_undistorter_.Undistort(right_raw),
                         right_undistorter_.pinhole(), levels);
  } else {
    ++summary_.mono_frames;
  }
  ++summary_.frames;
  DirectFrame frame;
  frame.t_ns = t_ns;
  const bool first = keyframe_ == nullptr && summary_.frames == 1;
  if (keyframe_ == nullptr) {
    // No keyframe yet (the first frame, or only weak ones so far): this
    // frame keeps the last pose and tries to become the keyframe.
    frame.T_w_c = T_w_last_;
    frame.lost = !first;
    if (frame.lost) ++summary_.lost;
  } else {
    const Eigen::Isometry3d T_w_pred =
        options_.constant_velocity ? T_w_last_ * velocity_ : T_w_last_;
    AlignmentState initial;
    initial.T_t_h = Rigid(T_w_pred.inverse() * keyframe_->T_w_c);
    initial.affine[0] = affine_[0];
    initial.affine[1] = affine_[1];
    frame.track = tracker_.Track(*keyframe_, left, stereo ? &right : nullptr,
                                 T_r_l_, initial);
    frame.tracked = frame.track.ok;
    frame.lost = !frame.track.ok;
    if (frame.lost) ++summary_.lost;
    frame.T_w_c = Rigid(frame.tracked ? keyframe_->T_w_c *
                                            frame.track.state.T_t_h.inverse()
                                      : T_w_pred);
  }
  velocity_ = frame.tracked ? Rigid(T_w_last_.inverse() * frame.T_w_c)
                            : Eigen::Isometry3d::Identity();
  T_w_last_ = frame.T_w_c;
  if (frame.tracked) {
    affine_[0] = frame.track.state.affine[0];
    affine_[1] = frame.track.state.affine[1];
  }

  // A new keyframe when there is none, tracking failed, the overlap dropped
  // or the frame moved far relative to the scene's depth.
  bool want = keyframe_ == nullptr || frame.lost;
  if (!want) {
    const double distance = frame.track.state.T_t_h.translation().norm();
    want =
        frame.track.overlap < options_.min_overlap ||
        distance > options_.max_distance_over_depth * keyframe_->median_depth_m;
  }
  if (want && stereo) {
    std::unique_ptr<DirectKeyframe> kf =
        MakeKeyframe(t_ns, left, right, frame.T_w_c, &frame.depth);
    if (kf != nullptr) {
      keyframe_ = std::move(kf);
      frame.keyframe = true;
      ++summary_.keyframes;
      affine_[0] = affine_[1] = Eigen::Vector2d::Zero();
    } else {
      ++summary_.weak_keyframes;
    }
  }
  return frame;
}

}  // namespace vio
