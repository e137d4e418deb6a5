#ifndef VIO_ESTIMATOR_WINDOW_H_
#define VIO_ESTIMATOR_WINDOW_H_

// The states of the sliding window as the Ceres problem sees them: per frame a
// pose block (7) and a speed-bias block (9), per camera an extrinsic block (7),
// in the DESIGN.md layouts. Frames are held by pointer so that their blocks
// keep their addresses while the window slides (the marginalisation prior
// refers to blocks by address).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <deque>
#include <memory>

#include "preintegration/imu_preintegration.h"

namespace vio {

// Named slots of the blocks (no magic offsets).
constexpr int kPoseP = 0;  // t_w_b (3)
constexpr int kPoseQ = 3;  // q_w_b (x, y, z, w)
constexpr int kSbV = 0;    // v_w (3)
constexpr int kSbBa = 3;   // b_a (3)
constexpr int kSbBg = 6;   // b_g (3)
constexpr int kMaxCameras = 2;

struct WindowFrame {
  int64_t id = 0;             // increasing over the run
  int64_t t_ns = 0;           // camera stamp [ns]
  int64_t t_imu_ns = 0;       // IMU time of the pose: t_ns + t_d [ns]
  double t_d_at_stamp = 0.0;  // the t_d that placed the pose [s]
  bool keyframe = false;
  // The vehicle stood still over the whole interval from the previous window
  // frame to this one (estimator/zero_velocity.h): a zero-motion factor ties
  // the two.
  bool still_link = false;
  // Gyroscope reading at t_imu_ns, bias not removed [rad/s]: the angular
  // rate for the predicted image velocity (estimator/image_velocity.h).
  Eigen::Vector3d gyr_b = Eigen::Vector3d::Zero();
  std::array<double, 7> pose{0, 0, 0, 0, 0, 0, 1};
  std::array<double, 9> speed_bias{};
  // The IMU interval from the previous window frame to this one; null for
  // the oldest frame, and for a frame whose interval spans an IMU gap (placed
  // by vision alone: estimator/imu_gaps.h).
  std::unique_ptr<ImuPreintegration> imu;

  Eigen::Map<Eigen::Vector3d> p_w_b() {
    return Eigen::Map<Eigen::Vector3d>(&pose[kPoseP]);
  }
  Eigen::Map<Eigen::Quaterniond> q_w_b() {
    return Eigen::Map<Eigen::Quaterniond>(&pose[kPoseQ]);
  }
  Eigen::Map<Eigen::Vector3d> v_w() {
    return Eigen::Map<Eigen::Vector3d>(&speed_bias[kSbV]);
  }
  Eigen::Map<Eigen::Vector3d> b_a() {
    return Eigen::Map<Eigen::Vector3d>(&speed_bias[kSbBa]);
  }
  Eigen::Map<Eigen::Vector3d> b_g() {
    return Eigen::Map<Eigen::Vector3d>(&speed_bias[kSbBg]);
  }
  Eigen::Vector3d p_w_b_value() const {
    return Eigen::Vector3d(pose.data() + kPoseP);
  }
  Eigen::Vector3d v_w_value() const {
    return Eigen::Vector3d(speed_bias.data() + kSbV);
  }
  Eigen::Vector3d b_g_value() const {
    return Eigen::Vector3d(speed_bias.data() + kSbBg);
  }
  Eigen::Isometry3d T_w_b() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::Quaterniond(pose.data() + kPoseQ)
                     .normalized()
                     .toRotationMatrix();
    T.translation() = Eigen::Vector3d(pose.data() + kPoseP);
    return T;
  }
};

struct Window {
  std::deque<std::unique_ptr<WindowFrame>> frames;              // oldest first
  std::array<std::array<double, 7>, kMaxCameras> extrinsics{};  // T_b_c
  int num_cameras = 1;
  double t_d = 0.0;  // camera-IMU time offset, t_imu = t_cam + t_d [s]

  // nullptr when the frame is not in the window.
  WindowFrame* Find(int64_t id) const {
    for (const auto& f : frames) {
      if (f->id == id) return f.get();
    }
    return nullptr;
  }
  int NumKeyframes() const {
    int n = 0;
    for (const auto& f : frames) n += f->keyframe ? 1 : 0;
    return n;
  }
  Eigen::Isometry3d T_b_c(int camera) const {
    const std::array<double, 7>& e = extrinsics[camera];
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() =
        Eigen::Quaterniond(e.data() + kPoseQ).normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(e.data() + kPoseP);
    return T;
  }
  // Requires the frame to be in the window.
  Eigen::Isometry3d T_w_c(int64_t id, int camera) const {
    return Find(id)->T_w_b() * T_b_c(camera);
  }
};

// The ambient pose array of an isometry.
inline std::array<double, 7> PoseArray(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return {T.translation().x(),
          T.translation().y(),
          T.translation().z(),
          q.x(),
          q.y(),
          q.z(),
          q.w()};
}

}  // namespace vio

#endif  // VIO_ESTIMATOR_WINDOW_H_
