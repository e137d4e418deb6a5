#ifndef VIO_TEST_TESTING_EUROC_V1_01_H_
#define VIO_TEST_TESTING_EUROC_V1_01_H_

// Access to the real EuRoC excerpt ../shared/data/euroc_V1_01_first5s for the
// frontend tests: its two camera calibrations and its images.
//
// The calibrations are the values of mav0/cam0/sensor.yaml and
// mav0/cam1/sensor.yaml, copied by hand until config/euroc_sequence
// (LoadEurocSequence) lands on main; then the tests will read the files.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>
#include <vector>

#include "geometry/camera_model.h"

namespace vio {
namespace testing {

inline std::string V101Dir() {
  return std::string(VIO_SHARED_DIR) + "/data/euroc_V1_01_first5s/mav0";
}

// Row-major 4x4 T_BS of sensor.yaml -> q_b_c, t_b_c.
inline void SetExtrinsic(const double (&T)[16], CameraCalibration* c) {
  Eigen::Matrix3d R;
  R << T[0], T[1], T[2], T[4], T[5], T[6], T[8], T[9], T[10];
  c->q_b_c = Eigen::Quaterniond(R).normalized();
  c->t_b_c = Eigen::Vector3d(T[3], T[7], T[11]);
}

inline CameraCalibration V101Cam0() {
  CameraCalibration c;  // 752x480, 20 Hz, radial-tangential
  c.fx = 458.654, c.fy = 457.296, c.cx = 367.215, c.cy = 248.375;
  c.distortion_coefficients << -0.28340811, 0.07395907, 0.00019359,
      1.76187114e-05;
  const double T[16] = {0.0148655429818,
                        -0.999880929698,
                        0.00414029679422,
                        -0.0216401454975,
                        0.999557249008,
                        0.0149672133247,
                        0.025715529948,
                        -0.064676986768,
                        -0.0257744366974,
                        0.00375618835797,
                        0.999660727178,
                        0.00981073058949,
                        0.0,
                        0.0,
                        0.0,
                        1.0};
  SetExtrinsic(T, &c);
  return c;
}

inline CameraCalibration V101Cam1() {
  CameraCalibration c;
  c.fx = 457.587, c.fy = 456.134, c.cx = 379.999, c.cy = 255.238;
  c.distortion_coefficients << -0.28368365, 0.07451284, -0.00010473,
      -3.55590700e-05;
  const double T[16] = {0.0125552670891,
                        -0.999755099723,
                        0.0182237714554,
                        -0.0198435579556,
                        0.999598781151,
                        0.0130119051815,
                        0.0251588363115,
                        0.0453689425024,
                        -0.0253898008918,
                        0.0179005838253,
                        0.999517347078,
                        0.00786212447038,
                        0.0,
                        0.0,
                        0.0,
                        1.0};
  SetExtrinsic(T, &c);
  return c;
}

// The (stamp, file) rows of mav0/cam<camera>/data.csv, header skipped.
inline std::vector<std::pair<int64_t, std::string>> V101ImageList(int camera) {
  std::vector<std::pair<int64_t, std::string>> rows;
  std::ifstream in(V101Dir() + "/cam" + std::to_string(camera) + "/data.csv");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t comma = line.find(',');
    std::string file = line.substr(comma + 1);
    while (!file.empty() && (file.back() == '\r' || file.back() == ' ')) {
      file.pop_back();
    }
    rows.emplace_back(std::stoll(line.substr(0, comma)), file);
  }
  return rows;
}

// Frame `index` of cam<camera> as 8-bit grey; empty when it does not exist.
inline cv::Mat V101Image(int camera, size_t index) {
  const auto rows = V101ImageList(camera);
  if (index >= rows.size()) return cv::Mat();
  return cv::imread(V101Dir() + "/cam" + std::to_string(camera) + "/data/" +
                        rows[index].second,
                    cv::IMREAD_GRAYSCALE);
}

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_EUROC_V1_01_H_
