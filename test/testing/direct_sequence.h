#ifndef VIO_TEST_TESTING_DIRECT_SEQUENCE_H_
#define VIO_TEST_TESTING_DIRECT_SEQUENCE_H_

// The real EuRoC excerpts as the direct method's tests use them: stereo
// image pairs (read with the dataset's image-list reader and OpenCV), the two
// calibrations from their sensor.yaml files, undistorted pyramids, and the
// ground-truth camera poses (ground truth is the body pose; cam0's T_BS
// from sensor.yaml gives the camera).

#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "config/euroc_sensor.h"
#include "dataset/euroc_reader.h"
#include "dataset/trajectory.h"
#include "frontend/image_pyramid.h"
#include "frontend/pinhole_undistorter.h"
#include "geometry/camera_model.h"

namespace vio {
namespace testing {

inline std::string SharedData(const std::string& name) {
  return std::string(VIO_SHARED_DIR) + "/data/" + name + "/mav0";
}

// The ground-truth pose at t_ns, interpolated (linear in position, slerp
// in rotation) between the two nearest samples; the stamp must lie inside.
inline StampedPose InterpolatePose(const Trajectory& gt, int64_t t_ns) {
  size_t i = 1;
  while (i + 1 < gt.size() && gt[i].t_ns < t_ns) ++i;
  const StampedPose& a = gt[i - 1];
  const StampedPose& b = gt[i];
  const double s =
      static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  StampedPose out;
  out.t_ns = t_ns;
  out.p_w_b = (1.0 - s) * a.p_w_b + s * b.p_w_b;
  out.q_w_b = a.q_w_b.slerp(s, b.q_w_b);
  return out;
}

inline Eigen::Isometry3d ToIsometry(const Eigen::Quaterniond& q,
                                    const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

// The ground-truth pose of camera `c` (T_w_b T_b_c) at t_ns.
inline Eigen::Isometry3d GroundTruthCamera(const Trajectory& gt,
                                           const CameraCalibration& c,
                                           int64_t t_ns) {
  const StampedPose p = InterpolatePose(gt, t_ns);
  return ToIsometry(p.q_w_b, p.p_w_b) * ToIsometry(c.q_b_c, c.t_b_c);
}

// A stereo sequence folder with cam0 and cam1 images.
struct StereoSequence {
  CameraCalibration cam0, cam1;
  std::vector<ImageEntry> left, right;  // listed and existing

  explicit StereoSequence(const std::string& mav0)
      : cam0(ReadEurocCameraYaml(mav0 + "/cam0/sensor.yaml")),
        cam1(ReadEurocCameraYaml(mav0 + "/cam1/sensor.yaml")) {
    int missing = 0;
    left = ReadEurocImageList(mav0 + "/cam0/data.csv", mav0 + "/cam0/data",
                              &missing);
    right = ReadEurocImageList(mav0 + "/cam1/data.csv", mav0 + "/cam1/data",
                               &missing);
  }

  // T_c1_c0: cam0 points into cam1.
  Eigen::Isometry3d T_c1_c0() const {
    return (ToIsometry(cam1.q_b_c, cam1.t_b_c).inverse() *
            ToIsometry(cam0.q_b_c, cam0.t_b_c));
  }
};

inline cv::Mat ReadGrey(const ImageEntry& entry) {
  return cv::imread(entry.path, cv::IMREAD_GRAYSCALE);
}

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_DIRECT_SEQUENCE_H_
