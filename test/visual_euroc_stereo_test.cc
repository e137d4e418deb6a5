// The stereo factor on real data: the first stereo pair of EuRoC V1_01 with
// the calibration from its sensor.yaml files. Corners found in cam0 and
// tracked into cam1 (OpenCV stands in for the frontend, which is not built
// yet) are explained by one inverse depth each: with T_BS read as T_b_c
// (p_b = R p_c + t), the remaining reprojection error must be at the level of
// the tracker's noise, and reading the calibration the other way round must
// not explain them.

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "config/yaml_reader.h"
#include "factors/check/visual_scene.h"
#include "factors/pose_manifold.h"
#include "factors/stereo_reprojection_factor.h"

namespace vio {
namespace {

const std::string kMav0 =
    std::string(VIO_SHARED_DIR) + "/data/euroc_V1_01_first5s/mav0/";
const std::string kFirstImage = "1403715273262142976.png";

struct Camera {
  Block7 T_b_c;  // from T_BS
  cv::Mat K, distortion;
  double focal_px = 0.0;  // fu
};

Camera LoadCamera(const std::string& name) {
  // EuRoC's files start with OpenCV's "%YAML:1.0", which yaml-cpp rejects.
  const std::string path = kMav0 + name + "/sensor.yaml";
  std::ifstream in(path);
  std::ostringstream text;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind('%', 0) != 0) text << line << "\n";
  }
  const YamlNode root = YamlNode::LoadString(text.str(), path);
  const std::vector<double> T = root.Child("T_BS").GetVector("data", 16);
  const std::vector<double> k = root.GetVector("intrinsics", 4);
  const std::vector<double> d = root.GetVector("distortion_coefficients", 4);
  Eigen::Isometry3d T_b_c;
  T_b_c.matrix() =
      Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(T.data());
  Camera c;
  c.T_b_c = BlockFromIsometry(T_b_c);
  c.K = (cv::Mat_<double>(3, 3) << k[0], 0, k[2], 0, k[1], k[3], 0, 0, 1);
  c.distortion = (cv::Mat_<double>(1, 4) << d[0], d[1], d[2], d[3]);
  c.focal_px = k[0];
  return c;
}

struct StereoMatches {
  std::vector<cv::Point2f> xy0, xy1;  // normalised coordinates
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
  std::vector<cv::Point2f> good0, good1;
  for (size_t i = 0; i < uv0.size(); ++i) {
    if (ok[i] && ok_back[i] && cv::norm(back[i] - uv0[i]) < 0.5) {
      good0.push_back(uv0[i]);
      good1.push_back(uv1[i]);
    }
  }
  StereoMatches m;
  if (good0.empty()) return m;
  cv::undistortPoints(good0, m.xy0, cam0.K, cam0.distortion);
  cv::undistortPoints(good1, m.xy1, cam1.K, cam1.distortion);
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
        new StereoReprojectionFactor(Eigen::Vector2d(m.xy0[i].x, m.xy0[i].y),
                                     Eigen::Vector2d(m.xy1[i].x, m.xy1[i].y),
                                     focal1_px / 1.0),
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
  FitDepths(m, cam0.T_b_c, cam1.T_b_c, cam1.focal_px, &errors, &rho);
  // Vertical disparity left after fitting depth: tracker noise only.
  EXPECT_LT(Median(errors), 0.5);
  // The room of V1_01 is a few metres across.
  const double median_depth = 1.0 / Median(rho);
  EXPECT_GT(median_depth, 1.0);
  EXPECT_LT(median_depth, 10.0);

  // T_BS read the wrong way round (as T_c_b) leaves pixels of error.
  std::vector<double> wrong_errors, wrong_rho;
  FitDepths(m, Inverse(cam0.T_b_c), Inverse(cam1.T_b_c), cam1.focal_px,
            &wrong_errors, &wrong_rho);
  EXPECT_GT(Median(wrong_errors), 5.0 * Median(errors));
}

}  // namespace
}  // namespace vio
