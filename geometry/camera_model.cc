#include "geometry/camera_model.h"

#include <cmath>

namespace vio {
namespace {

// Below this radius the equidistant model is the identity to machine
// precision (th_d / r = 1 + O(r^2)), and its Jacobian is I.
constexpr double kMinRadius = 1e-10;

Eigen::Vector2d DistortRadTan(const Eigen::Vector4d& c,
                              const Eigen::Vector2d& xy, Eigen::Matrix2d* J) {
  const double k1 = c[0], k2 = c[1], p1 = c[2], p2 = c[3];
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double k = 1.0 + k1 * r2 + k2 * r2 * r2;
  Eigen::Vector2d out(k * x + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
                      k * y + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y);
  if (J) {
    // d k / d x = (k1 + 2 k2 r2) * 2 x, likewise for y; then product rule on
    // each term of x_d and y_d.
    const double dk = k1 + 2.0 * k2 * r2;
    (*J)(0, 0) = k + 2.0 * x * x * dk + 2.0 * p1 * y + 6.0 * p2 * x;
    (*J)(0, 1) = 2.0 * x * y * dk + 2.0 * p1 * x + 2.0 * p2 * y;
    (*J)(1, 0) = 2.0 * x * y * dk + 2.0 * p1 * x + 2.0 * p2 * y;
    (*J)(1, 1) = k + 2.0 * y * y * dk + 6.0 * p1 * y + 2.0 * p2 * x;
  }
  return out;
}

Eigen::Vector2d DistortEquidistant(const Eigen::Vector4d& c,
                                   const Eigen::Vector2d& xy,
                                   Eigen::Matrix2d* J) {
  const double r = xy.norm();
  if (r < kMinRadius) {
    if (J) J->setIdentity();
    return xy;
  }
  const double th = std::atan(r);
  const double t2 = th * th;
  const double poly = 1.0 + t2 * (c[0] + t2 * (c[1] + t2 * (c[2] + t2 * c[3])));
  const double th_d = th * poly;
  const double s = th_d / r;
  if (J) {
    // xy_d = s(r) xy  =>  J = s I + (ds/dr) xy xy^T / r, with
    // ds/dr = (th_d'(th) th'(r) r - th_d) / r^2, th'(r) = 1 / (1 + r^2),
    // th_d'(th) = 1 + 3 k1 th^2 + 5 k2 th^4 + 7 k3 th^6 + 9 k4 th^8.
    const double dthd_dth =
        1.0 + t2 * (3.0 * c[0] +
                    t2 * (5.0 * c[1] + t2 * (7.0 * c[2] + t2 * 9.0 * c[3])));
    const double ds_dr = (dthd_dth / (1.0 + r * r) * r - th_d) / (r * r);
    *J = s * Eigen::Matrix2d::Identity() + (ds_dr / r) * xy * xy.transpose();
  }
  return s * xy;
}

}  // namespace

bool CameraCalibration::Validate(std::string* message) const {
  auto fail = [&](const std::string& text) {
    *message = text;
    return false;
  };
  if (width <= 0 || height <= 0) {
    return fail("resolution must be > 0 (got " + std::to_string(width) + " x " +
                std::to_string(height) + ")");
  }
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    return fail("rate_hz must be > 0 (got " + std::to_string(rate_hz) + ")");
  }
  if (!(std::isfinite(fx) && std::isfinite(fy) && fx > 0.0 && fy > 0.0)) {
    return fail("intrinsics: focal lengths must be > 0 (got " +
                std::to_string(fx) + ", " + std::to_string(fy) + ")");
  }
  if (!std::isfinite(cx) || !std::isfinite(cy)) {
    return fail("intrinsics: principal point must be finite");
  }
  if (!distortion_coefficients.allFinite()) {
    return fail("distortion_coefficients must be finite");
  }
  if (!t_b_c.allFinite() || !q_b_c.coeffs().allFinite() ||
      std::abs(q_b_c.norm() - 1.0) > 1e-6) {
    return fail("T_BS must be a finite rigid transform");
  }
  return true;
}

bool ParseDistortionModel(const std::string& name, DistortionModel* model) {
  if (name == "radial-tangential" || name == "radtan") {
    *model = DistortionModel::kRadialTangential;
  } else if (name == "equidistant" || name == "fisheye") {
    *model = DistortionModel::kEquidistant;
  } else if (name == "none") {
    *model = DistortionModel::kNone;
  } else {
    return false;
  }
  return true;
}

const char* DistortionModelName(DistortionModel model) {
  switch (model) {
    case DistortionModel::kRadialTangential:
      return "radial-tangential";
    case DistortionModel::kEquidistant:
      return "equidistant";
    case DistortionModel::kNone:
      break;
  }
  return "none";
}

CameraModel::CameraModel(const CameraCalibration& calibration)
    : calibration_(calibration) {}

Eigen::Vector2d CameraModel::Distort(const Eigen::Vector2d& xy,
                                     Eigen::Matrix2d* d_xyd_d_xy) const {
  const Eigen::Vector4d& c = calibration_.distortion_coefficients;
  switch (calibration_.distortion) {
    case DistortionModel::kRadialTangential:
      return DistortRadTan(c, xy, d_xyd_d_xy);
    case DistortionModel::kEquidistant:
      return DistortEquidistant(c, xy, d_xyd_d_xy);
    case DistortionModel::kNone:
      break;
  }
  if (d_xyd_d_xy) d_xyd_d_xy->setIdentity();
  return xy;
}

bool CameraModel::Undistort(const Eigen::Vector2d& xy_d,
                            Eigen::Vector2d* xy) const {
  // Gauss-Newton on Distort(xy) = xy_d from xy = xy_d; the distortion is
  // mild inside the field of view, so a handful of iterations suffice.
  constexpr int kMaxIterations = 30;
  constexpr double kTolerance = 1e-10;
  Eigen::Vector2d x = xy_d;
  for (int i = 0; i < kMaxIterations; ++i) {
    Eigen::Matrix2d J;
    const Eigen::Vector2d e = Distort(x, &J) - xy_d;
    if (!e.allFinite()) return false;
    if (e.norm() < kTolerance) {
      *xy = x;
      return true;
    }
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-12)) return false;
    x -= J.inverse() * e;
  }
  const Eigen::Vector2d e = Distort(x) - xy_d;
  if (!(e.norm() < kTolerance)) return false;
  *xy = x;
  return true;
}

Eigen::Vector2d CameraModel::NormalizedToPixel(
    const Eigen::Vector2d& xy) const {
  const Eigen::Vector2d d = Distort(xy);
  return {calibration_.fx * d.x() + calibration_.cx,
          calibration_.fy * d.y() + calibration_.cy};
}

bool CameraModel::PixelToNormalized(const Eigen::Vector2d& uv,
                                    Eigen::Vector2d* xy) const {
  const Eigen::Vector2d xy_d((uv.x() - calibration_.cx) / calibration_.fx,
                             (uv.y() - calibration_.cy) / calibration_.fy);
  return Undistort(xy_d, xy);
}

bool CameraModel::Project(const Eigen::Vector3d& p_c,
                          Eigen::Vector2d* uv) const {
  if (!(p_c.z() > kMinDepth) || !p_c.allFinite()) return false;
  *uv = NormalizedToPixel(p_c.head<2>() / p_c.z());
  return true;
}

bool CameraModel::InImage(const Eigen::Vector2d& uv) const {
  return uv.x() >= 0.0 && uv.y() >= 0.0 && uv.x() < calibration_.width &&
         uv.y() < calibration_.height;
}

}  // namespace vio
