// The stereo factor on real data: the first stereo pair of EuRoC V1_01 with
// the calibration from its sensor.yaml files. Corners found in cam0 and
// tracked into cam1 (OpenCV's KLT stands in for the frontend's tracker, which
// is not built yet; the calibration comes through config/euroc_sensor.h and
// geometry/camera_model.h) are explained by one inverse depth each: with T_BS
// read as T_b_c (p_b = R p_c + t), the remaining reprojection error must be at
// the level of the tracker's noise, and reading the calibration the other way
// round must not explain them.

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <string>
#include <vector>

#include "config/euroc_sensor.h"
#include "factors/check/visual_scene.h"
#include "factors/pose_manifold.h"
#include "factors/stereo_reprojection_factor.h"
#include "geometry/camera_model.h"

namespace vio {
namespace {

const std::string kMav0 =
    std::string(VIO_SHARED_DIR) + "/data/euroc_V1_01_first5s/mav0/";
const std::string kFirstImage = "1403715273262142976.png";

// A camera as the project reads it: config/euroc_sensor.h's sensor.yaml
// reader and geometry's camera model.
struct Camera {
  CameraModel model;
  Block7 T_b_c;
};

Camera LoadCamera(const std::string& name) {
  const CameraCalibration calibration =
      ReadEurocCameraYaml(kMav0 + name + "/sensor.yaml");
  Block7 T_b_c;
  T_b_c << calibration.t_b_c, calibration.q_b_c.coeffs();
  return {CameraModel(calibration), T_b_c};
}

struct StereoMatches {
  std::vector<Eigen::Vector2d> xy0, xy1;  // normalised coordinates
};

// Corners of cam0 tracked into cam1 with pyramidal LK, kept when tracking
// back lands within 0.5 px of the start.
StereoMatches MatchFirstPair(const Camera& cam0, const Camera& cam1) {
  const cv::Mat img0 =
      cv::imread(kMav0 + "cam0/data/" + kFirstImage, cv::IMREAD_GRAYSCALE);
  const cv::Mat img1 =
      cv::imread(kMav0 + "cam1/data/" + kFirstImage, cv::IMREAD_GRAYSCALE);
  EXPECT_FALSE(img0.empty() || img1.empty()) << "cannot read " << kMav0;
  if (img0.empty() || img1.empty()) return {};
  std::vector<cv::Point2f> uv0, uv1, back;
  cv::goodFeaturesToTrack(img0, uv0, 300, 0.01, 15);
  std::vector<uchar> ok, ok_back;
  std::vector<float> err;
  cv::calcOpticalFlowPyrLK(img0, img1, uv0, uv1, ok, err);
  cv::calcOpticalFlowPyrLK(img1, img0, uv1, back, ok_back, err);
  StereoMatches m;
  for (size_t i = 0; i < uv0.size(); ++i) {
    Eigen::Vector2d xy0, xy1;
    if (ok[i] && ok_back[i] && cv::norm(back[i] - uv0[i]) < 0.5 &&
        cam0.model.PixelToNormalized({uv0[i].x, uv0[i].y}, &xy0) &&
        cam1.model.PixelToNormalized({uv1[i].x, uv1[i].y}, &xy1)) {
      m.xy0.push_back(xy0);
      m.xy1.push_back(xy1);
    }
  }
  return m;
}

Block7 Inverse(const Block7& T) {
  return BlockFromIsometry(IsometryFromBlock(T).inverse());
}

// Fits one inverse depth per match with StereoReprojectionFactor (sigma =
// 1 px, so residuals are pixels) and the extrinsics held fixed; returns the
// pixel errors and the fitted inverse depths.
void FitDepths(const StereoMatches& m, Block7 T_b_c0, Block7 T_b_c1,
               double focal1_px, std::vector<double>* errors_px,
               std::vector<double>* rho) {
  ceres::Problem problem;
  rho->assign(m.xy0.size(), 0.2);  // start every point at 5 m
  for (size_t i = 0; i < m.xy0.size(); ++i) {
    problem.AddResidualBlock(
        new StereoReprojectionFactor(m.xy0[i], m.xy1[i], focal1_px / 1.0),
        nullptr, T_b_c0.data(), T_b_c1.data(), &(*rho)[i]);
  }
  for (Block7* T : {&T_b_c0, &T_b_c1}) {
    problem.SetManifold(T->data(), new PoseManifold);
    problem.SetParameterBlockConstant(T->data());
  }
  ceres::Solver::Options options;
  options.max_num_iterations = 50;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  ASSERT_TRUE(summary.IsSolutionUsable());
  std::vector<double> residuals;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, &residuals,
                   nullptr, nullptr);
  errors_px->clear();
  for (size_t i = 0; i + 1 < residuals.size(); i += 2) {
    errors_px->push_back(std::hypot(residuals[i], residuals[i + 1]));
  }
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

TEST(VisualEurocStereo, SensorYamlExtrinsicsExplainRealStereoMatches) {
  const Camera cam0 = LoadCamera("cam0");
  const Camera cam1 = LoadCamera("cam1");
  const StereoMatches m = MatchFirstPair(cam0, cam1);
  ASSERT_GE(m.xy0.size(), 50u);

  std::vector<double> errors, rho;
  FitDepths(m, cam0.T_b_c, cam1.T_b_c, cam1.model.focal(), &errors, &rho);
  // Vertical disparity left after fitting depth: tracker noise only.
  EXPECT_LT(Median(errors), 0.5);
  // The room of V1_01 is a few metres across.
  const double median_depth = 1.0 / Median(rho);
  EXPECT_GT(median_depth, 1.0);
  EXPECT_LT(median_depth, 10.0);

  // T_BS read the wrong way round (as T_c_b) leaves pixels of error.
  std::vector<double> wrong_errors, wrong_rho;
  FitDepths(m, Inverse(cam0.T_b_c), Inverse(cam1.T_b_c), cam1.model.focal(),
            &wrong_errors, &wrong_rho);
  EXPECT_GT(Median(wrong_errors), 5.0 * Median(errors));
}

}  // namespace
}  // namespace vio
