#ifndef VIO_ESTIMATOR_TRIANGULATION_H_
#define VIO_ESTIMATOR_TRIANGULATION_H_

// Linear multi-view triangulation of one landmark (the DLT of Hartley and
// Zisserman, "Multiple View Geometry", 2nd ed., sec. 12.2) and the checks that
// decide whether it may enter the problem. The solve then refines the point
// through its inverse depth.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "estimator/estimator_options.h"

namespace vio {

// One sighting of the landmark: the camera's pose in the world and the
// undistorted normalised coordinate (x / z, y / z) it measured.
struct TriangulationView {
  Eigen::Isometry3d T_w_c = Eigen::Isometry3d::Identity();
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // [-]
};

enum class TriangulationStatus {
  kOk,
  kTooFewViews,  // fewer than options.min_observations views
  kLowParallax,  // the widest pair of rays is narrower than min_parallax_deg
  kDegenerate,   // the DLT has no finite solution
  kBadDepth,     // behind or too close to a camera, or too far from views[0]
};

const char* TriangulationStatusName(TriangulationStatus status);

// Largest angle between two of the views' rays, in the world frame [deg]
// (rotation compensated: pure rotation gives 0).
double MaxRayAngleDeg(const std::vector<TriangulationView>& views);

// Triangulates the point seen by all views. views[0] is the anchor: its depth
// must lie in [min_depth_m, max_depth_m]; every other view's depth must be at
// least min_depth_m. On kOk writes the point in the world [m] and its depth in
// the anchor camera [m]; otherwise leaves them untouched.
TriangulationStatus Triangulate(const std::vector<TriangulationView>& views,
                                const TriangulationOptions& options,
                                Eigen::Vector3d* p_w, double* anchor_depth_m);

}  // namespace vio

#endif  // VIO_ESTIMATOR_TRIANGULATION_H_
