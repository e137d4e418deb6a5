// PlaceCameraByPnp (declared in structure_from_motion.h): one camera placed
// on known points, for the mono structure from motion and the stereo start.
#include <Eigen/Geometry>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "estimator/structure_from_motion.h"

namespace vio {
namespace {

cv::Mat Identity3() { return cv::Mat::eye(3, 3, CV_64F); }

}  // namespace

bool PlaceCameraByPnp(const SfmFrame& frame,
                      const std::map<int64_t, Eigen::Vector3d>& points,
                      const Eigen::Isometry3d* guess, const SfmOptions& options,
                      Eigen::Isometry3d* T_v_c, int* inliers_out) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const auto& [id, xy] : frame.xy) {
    const auto it = points.find(id);
    if (it == points.end()) continue;
    object.emplace_back(it->second.x(), it->second.y(), it->second.z());
    image.emplace_back(xy.x(), xy.y());
  }
  *inliers_out = 0;
  if (static_cast<int>(object.size()) < options.min_pnp_inliers) return false;
  const double threshold = options.pnp_threshold_px / options.focal_px;
  cv::Mat rvec, tvec;
  // The points that agree with the pose (rvec, tvec) within the threshold.
  // The image points are normalised (identity intrinsics): a point's
  // projection is its camera coordinates over depth.
  auto agreeing = [&](std::vector<cv::Point3d>* o,
                      std::vector<cv::Point2d>* i) {
    cv::Mat R;
    cv::Rodrigues(rvec, R);
    const cv::Matx33d Rm(R);
    const cv::Vec3d t(tvec);
    for (size_t k = 0; k < object.size(); ++k) {
      const cv::Vec3d p_c = Rm * cv::Vec3d(object[k]) + t;
      if (p_c[2] <= 0.0) continue;
      const cv::Point2d projected(p_c[0] / p_c[2], p_c[1] / p_c[2]);
      if (cv::norm(projected - image[k]) <= threshold) {
        o->push_back(object[k]);
        i->push_back(image[k]);
      }
    }
  };
  std::vector<int> ransac_inliers;
  bool placed = false;
  if (guess != nullptr) {
    // The guess as OpenCV's object-to-camera transform T_c_v.
    const Eigen::Isometry3d T_c_v = guess->inverse();
    const Eigen::AngleAxisd aa(T_c_v.linear());
    const Eigen::Vector3d r = aa.angle() * aa.axis();
    rvec = (cv::Mat_<double>(3, 1) << r.x(), r.y(), r.z());
    tvec = (cv::Mat_<double>(3, 1) << T_c_v.translation().x(),
            T_c_v.translation().y(), T_c_v.translation().z());
    const bool ok = cv::solvePnPRansac(
        object, image, Identity3(), cv::noArray(), rvec, tvec,
        /*useExtrinsicGuess=*/true, /*iterationsCount=*/100,
        static_cast<float>(threshold), 0.99, ransac_inliers,
        cv::SOLVEPNP_ITERATIVE);
    *inliers_out = static_cast<int>(ransac_inliers.size());
    // Its inliers as OpenCV reports them, but only when the pose it returns
    // agrees with as many: else (outlier sightings, see the header) the
    // camera is placed again without the guess.
    if (ok && *inliers_out >= options.min_pnp_inliers) {
      std::vector<cv::Point3d> object_in;
      std::vector<cv::Point2d> image_in;
      agreeing(&object_in, &image_in);
      placed = static_cast<int>(object_in.size()) >= options.min_pnp_inliers;
    }
    if (!placed) {
      rvec = cv::Mat();
      tvec = cv::Mat();
      ransac_inliers.clear();
    }
  }
  if (!placed) {
    const bool ok = cv::solvePnPRansac(
        object, image, Identity3(), cv::noArray(), rvec, tvec,
        /*useExtrinsicGuess=*/false, /*iterationsCount=*/100,
        static_cast<float>(threshold), 0.99, ransac_inliers,
        cv::SOLVEPNP_ITERATIVE);
    *inliers_out = static_cast<int>(ransac_inliers.size());
    if (!ok) return false;
    // RANSAC counts its inliers against its best sample's model, not
    // against the pose it returns: count them again against that pose, and
    // refine it on them (Levenberg-Marquardt on the reprojection error).
    std::vector<cv::Point3d> object_in;
    std::vector<cv::Point2d> image_in;
    agreeing(&object_in, &image_in);
    if (static_cast<int>(object_in.size()) >= options.min_pnp_inliers) {
      cv::solvePnPRefineLM(object_in, image_in, Identity3(), cv::noArray(),
                           rvec, tvec);
      object_in.clear();
      image_in.clear();
      agreeing(&object_in, &image_in);
    }
    *inliers_out = static_cast<int>(object_in.size());
  }
  if (*inliers_out < options.min_pnp_inliers) return false;
  const Eigen::Vector3d rv(rvec.at<double>(0), rvec.at<double>(1),
                           rvec.at<double>(2));
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  if (rv.norm() > 0.0) {
    result.linear() = Eigen::AngleAxisd(rv.norm(), rv.normalized()).matrix();
  }
  result.translation() = Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1),
                                         tvec.at<double>(2));
  *T_v_c = result.inverse();
  return T_v_c->matrix().allFinite();
}

}  // namespace vio
