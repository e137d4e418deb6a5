#ifndef VIO_GEOMETRY_CAMERA_MODEL_H_
#define VIO_GEOMETRY_CAMERA_MODEL_H_

// Camera models of the EuRoC / Kalibr sensor.yaml: pinhole projection with
// radial-tangential (OpenCV's k1, k2, p1, p2) or equidistant (fisheye, k1..k4)
// distortion, and the camera's extrinsic T_b_c (p_b = R_b_c p_c + t_b_c).
//
// Coordinates: a point p_c in the camera frame projects to the undistorted
// normalised coordinates xy = (x / z, y / z); distortion maps xy to xy_d; the
// pixel is uv = (fx * x_d + cx, fy * y_d + cy).
//
//   radtan:      r2 = x^2 + y^2, k = 1 + k1 r2 + k2 r2^2
//                x_d = k x + 2 p1 x y + p2 (r2 + 2 x^2)
//                y_d = k y + p1 (r2 + 2 y^2) + 2 p2 x y
//   equidistant: r = |xy|, th = atan(r),
//                th_d = th (1 + k1 th^2 + k2 th^4 + k3 th^6 + k4 th^8),
//                xy_d = (th_d / r) xy
// (Kannala and Brandt, PAMI 2006; the OpenCV and Kalibr conventions.)

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

namespace vio {

enum class DistortionModel { kNone, kRadialTangential, kEquidistant };

// Everything a camera's sensor.yaml says about it.
struct CameraCalibration {
  int width = 752;   // [px]
  int height = 480;  // [px]
  double rate_hz = 20.0;
  double fx = 458.654, fy = 457.296;  // focal lengths [px]
  double cx = 367.215, cy = 248.375;  // principal point [px]
  DistortionModel distortion = DistortionModel::kRadialTangential;
  // radtan: k1, k2, p1, p2; equidistant: k1, k2, k3, k4; none: unused.
  Eigen::Vector4d distortion_coefficients{-0.28340811, 0.07395907, 0.00019359,
                                          1.76187114e-05};
  // Extrinsic: pose of the camera in the body (IMU) frame, T_BS of EuRoC.
  Eigen::Quaterniond q_b_c = Eigen::Quaterniond::Identity();
  Eigen::Vector3d t_b_c = Eigen::Vector3d::Zero();  // [m]

  // True when sizes, rate and focal lengths are > 0, every value is finite
  // and q_b_c is a unit quaternion; else false with a message that starts
  // with the offending field.
  bool Validate(std::string* message) const;
};

// Parses "radial-tangential"/"radtan", "equidistant"/"fisheye", "none";
// returns false for anything else.
bool ParseDistortionModel(const std::string& name, DistortionModel* model);
const char* DistortionModelName(DistortionModel model);

class CameraModel {
 public:
  explicit CameraModel(const CameraCalibration& calibration);

  const CameraCalibration& calibration() const { return calibration_; }
  // Mean focal length [px]: converts pixel noise to normalised-plane noise.
  double focal() const { return 0.5 * (calibration_.fx + calibration_.fy); }

  // Undistorted -> distorted normalised coordinates, with the optional 2x2
  // Jacobian d xy_d / d xy.
  Eigen::Vector2d Distort(const Eigen::Vector2d& xy,
                          Eigen::Matrix2d* d_xyd_d_xy = nullptr) const;

  // Inverse of Distort by Gauss-Newton from xy_d. Returns false when it does
  // not converge to 1e-10 (far outside the calibrated field of view).
  bool Undistort(const Eigen::Vector2d& xy_d, Eigen::Vector2d* xy) const;

  // Pixel <-> undistorted normalised coordinates.
  Eigen::Vector2d NormalizedToPixel(const Eigen::Vector2d& xy) const;
  bool PixelToNormalized(const Eigen::Vector2d& uv, Eigen::Vector2d* xy) const;

  // Projects a point in the camera frame to a distorted pixel. Returns false
  // for points with z <= kMinDepth (behind or at the camera).
  static constexpr double kMinDepth = 1e-6;  // [m]
  bool Project(const Eigen::Vector3d& p_c, Eigen::Vector2d* uv) const;

  // True when the pixel lies inside the image (0 <= u < width, same for v).
  bool InImage(const Eigen::Vector2d& uv) const;

 private:
  CameraCalibration calibration_;
};

}  // namespace vio

#endif  // VIO_GEOMETRY_CAMERA_MODEL_H_
