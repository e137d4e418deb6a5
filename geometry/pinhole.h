#ifndef VIO_GEOMETRY_PINHOLE_H_
#define VIO_GEOMETRY_PINHOLE_H_

// The distortion-free pinhole camera of an undistorted image (and of each
// level of its pyramid), as the direct method uses it:
//   uv = (fx x / z + cx, fy y / z + cy)
// with OpenCV's pixel convention: u right, v down, the centre of the top-left
// pixel at (0, 0). The projection is scale invariant, so it takes a
// homogeneous point h = s * p (any s > 0) as readily as the point p itself;
// the direct method passes h = rho * p, which stays finite as the inverse
// depth rho goes to 0.

#include <Eigen/Core>

namespace vio {

struct Pinhole {
  double fx = 0.0, fy = 0.0;  // focal lengths [px]
  double cx = 0.0, cy = 0.0;  // principal point [px]

  // Pixel of the (homogeneous) point h; h.z() must be > 0.
  Eigen::Vector2d Project(const Eigen::Vector3d& h) const {
    return {fx * h.x() / h.z() + cx, fy * h.y() / h.z() + cy};
  }

  // d uv / d h (2 x 3) at h:
  //   [fx / z, 0, -fx x / z^2;  0, fy / z, -fy y / z^2].
  Eigen::Matrix<double, 2, 3> ProjectJacobian(const Eigen::Vector3d& h) const {
    const double iz = 1.0 / h.z();
    Eigen::Matrix<double, 2, 3> J;
    J << fx * iz, 0.0, -fx * h.x() * iz * iz,  //
        0.0, fy * iz, -fy * h.y() * iz * iz;
    return J;
  }

  // The bearing (x, y, 1) of a pixel: the point at depth 1 seen there.
  Eigen::Vector3d Bearing(const Eigen::Vector2d& uv) const {
    return {(uv.x() - cx) / fx, (uv.y() - cy) / fy, 1.0};
  }

  // The pinhole of the image halved by averaging 2 x 2 blocks: pixel u' of
  // the half image covers pixels 2u' and 2u' + 1, whose centres average to
  // 2u' + 0.5, so u = 2u' + 0.5, i.e. u' = (u + 0.5) / 2 - 0.5.
  Pinhole Halved() const {
    return {0.5 * fx, 0.5 * fy, 0.5 * (cx + 0.5) - 0.5, 0.5 * (cy + 0.5) - 0.5};
  }
};

}  // namespace vio

#endif  // VIO_GEOMETRY_PINHOLE_H_
