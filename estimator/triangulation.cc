#include "estimator/triangulation.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace vio {

const char* TriangulationStatusName(TriangulationStatus status) {
  switch (status) {
    case TriangulationStatus::kOk:
      return "ok";
    case TriangulationStatus::kTooFewViews:
      return "too few views";
    case TriangulationStatus::kLowParallax:
      return "low parallax";
    case TriangulationStatus::kDegenerate:
      return "degenerate";
    case TriangulationStatus::kBadDepth:
      return "bad depth";
  }
  return "unknown";
}

double MaxRayAngleDeg(const std::vector<TriangulationView>& views) {
  std::vector<Eigen::Vector3d> rays_w;
  rays_w.reserve(views.size());
  for (const TriangulationView& v : views) {
    rays_w.push_back(v.T_w_c.linear() * v.xy.homogeneous().normalized());
  }
  // The smallest cosine over all pairs is the widest angle.
  double min_cos = 1.0;
  for (size_t i = 0; i < rays_w.size(); ++i) {
    for (size_t j = i + 1; j < rays_w.size(); ++j) {
      min_cos = std::min(min_cos, rays_w[i].dot(rays_w[j]));
    }
  }
  return std::acos(std::clamp(min_cos, -1.0, 1.0)) * 180.0 / M_PI;
}

TriangulationStatus Triangulate(const std::vector<TriangulationView>& views,
                                const TriangulationOptions& options,
                                Eigen::Vector3d* p_w, double* anchor_depth_m) {
  if (static_cast<int>(views.size()) < options.min_observations ||
      views.size() < 2) {
    return TriangulationStatus::kTooFewViews;
  }
  if (MaxRayAngleDeg(views) < options.min_parallax_deg) {
    return TriangulationStatus::kLowParallax;
  }
  // With P = [R_c_w | t_c_w] (3 x 4) and the homogeneous point X, the
  // measurement x = P1 X / P3 X, y = P2 X / P3 X gives two linear equations
  // per view: (x P3 - P1) X = 0 and (y P3 - P2) X = 0. X is the right singular
  // vector of the stacked system with the smallest singular value.
  Eigen::MatrixXd A(2 * views.size(), 4);
  for (size_t i = 0; i < views.size(); ++i) {
    const Eigen::Isometry3d T_c_w = views[i].T_w_c.inverse();
    Eigen::Matrix<double, 3, 4> P;
    P.leftCols<3>() = T_c_w.linear();
    P.col(3) = T_c_w.translation();
    A.row(2 * i) = views[i].xy.x() * P.row(2) - P.row(0);
    A.row(2 * i + 1) = views[i].xy.y() * P.row(2) - P.row(1);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  // A point at infinity (w ~ 0) has no finite position.
  if (!X.allFinite() || std::abs(X.w()) < 1e-12 * X.head<3>().norm()) {
    return TriangulationStatus::kDegenerate;
  }
  const Eigen::Vector3d point_w = X.head<3>() / X.w();
  if (!point_w.allFinite()) return TriangulationStatus::kDegenerate;
  for (size_t i = 0; i < views.size(); ++i) {
    const double depth = (views[i].T_w_c.inverse() * point_w).z();
    if (!(depth >= options.min_depth_m)) return TriangulationStatus::kBadDepth;
    if (i == 0 && !(depth <= options.max_depth_m)) {
      return TriangulationStatus::kBadDepth;
    }
  }
  *p_w = point_w;
  *anchor_depth_m = (views[0].T_w_c.inverse() * point_w).z();
  return TriangulationStatus::kOk;
}

}  // namespace vio
