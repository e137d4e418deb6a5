// Tests of tools/curve_fitting: the hand LM against Ceres on the notes'
// exercise, the damping updates step by step, the robust kernels, and the
// tool itself.

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/curve_fitting/curve_ceres.h"
#include "tools/curve_fitting/curve_problem.h"
#include "tools/curve_fitting/levenberg_marquardt.h"
#include "tools/curve_fitting/robust_irls.h"

namespace vio {
namespace {

const Eigen::Vector3d kTruth(1.0, 2.0, 1.0);

double MaxRelativeDifference(const Eigen::Vector3d& x,
                             const Eigen::Vector3d& y) {
  return (x - y).cwiseAbs().cwiseQuotient(y.cwiseAbs()).maxCoeff();
}

LmSummary FitWithLm(const CurveSamples& samples, const LmOptions& options) {
  return SolveLevenbergMarquardt(CurveResiduals(samples),
                                 Eigen::VectorXd::Zero(3), options);
}

TEST(CurveFitting, CeresAndHandLmReachTheSameMinimumOnTheDefaultProblem) {
  const CurveSamples samples = MakeCurveSamples(CurveProblemOptions{});
  const CeresFitResult ceres =
      FitCurveWithCeres(samples, Eigen::Vector3d::Zero(), CeresFitOptions{});
  ASSERT_TRUE(ceres.summary.IsSolutionUsable());
  for (LmDamping damping : {LmDamping::kNielsen, LmDamping::kMarquardt}) {
    LmOptions options;
    options.damping = damping;
    const LmSummary lm = FitWithLm(samples, options);
    SCOPED_TRACE(LmDampingName(damping));
    EXPECT_EQ(lm.termination, LmTermination::kGradient);
    EXPECT_LT(MaxRelativeDifference(lm.p.head<3>(), ceres.p), 1e-6);
    EXPECT_NEAR(lm.final_chi2, 2.0 * ceres.summary.final_cost, 1e-9);
    // The start is far off: the cost must have come down by orders.
    EXPECT_LT(lm.final_chi2, 1e-2 * lm.initial_chi2);
  }
}

TEST(CurveFitting, EstimateIsWithinThreeSigmaOfTheTruth) {
  const CurveSamples samples = MakeCurveSamples(CurveProblemOptions{});
  const LmSummary lm = FitWithLm(samples, LmOptions{});
  Eigen::Matrix3d covariance;
  ASSERT_TRUE(CurveCovariance(samples, lm.p.head<3>(), &covariance));
  for (int i = 0; i < 3; ++i) {
    const double sigma = std::sqrt(covariance(i, i));
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(std::abs(lm.p[i] - kTruth[i]), 3.0 * sigma) << "parameter " << i;
  }
}

TEST(CurveSampleCost, JacobianMatchesNumericDiff) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const double x = 0.5 * (uniform(rng) + 1.0);
    const CurveSampleCost cost(x, 10.0 * uniform(rng));
    double p[3] = {uniform(rng), 2.0 * uniform(rng), uniform(rng)};
    const double* parameters[] = {p};
    ceres::NumericDiffOptions numeric;
    const std::vector<const ceres::Manifold*> euclidean(1, nullptr);
    ceres::GradientChecker checker(&cost, &euclidean, numeric);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters, 1e-8, &results)) << results.error_log;
  }
}

TEST(CurveResiduals, MatchTheCeresCostFunction) {
  const CurveSamples samples = MakeCurveSamples(CurveProblemOptions{});
  const Eigen::VectorXd p = Eigen::Vector3d(0.3, -0.2, 0.7);
  Eigen::VectorXd r;
  Eigen::MatrixXd d_r_d_p;
  ASSERT_TRUE(CurveResiduals(samples)(p, &r, &d_r_d_p));
  for (size_t i = 0; i < samples.x.size(); i += 7) {
    const CurveSampleCost cost(samples.x[i], samples.y[i]);
    const double* parameters[] = {p.data()};
    double residual = 0.0, jacobian[3];
    double* jacobians[] = {jacobian};
    ASSERT_TRUE(cost.Evaluate(parameters, &residual, jacobians));
    EXPECT_DOUBLE_EQ(r[i], residual);
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(d_r_d_p(i, k), jacobian[k]);
  }
}

// Squared Mahalanobis distance of p from the truth, with the covariance of
// the plain fit to the same samples without outliers.
double Mahalanobis2(const Eigen::Vector3d& p, const Eigen::Matrix3d& cov) {
  const Eigen::Vector3d d = p - kTruth;
  return d.dot(cov.ldlt().solve(d));
}

TEST(CurveFitting, RobustFitsIgnoreTenPercentOutliersWhereThePlainFitDoesNot) {
  // 99.9 % quantile of chi^2 with 3 degrees of freedom: a robust fit must be
  // as close to the truth as a clean fit would be. The plain fit must miss by
  // far more (d^2 > 100, i.e. 10 sigma along the worst direction).
  constexpr double kNear = 16.27, kFar = 100.0;
  for (uint32_t seed : {42u, 1u, 2u, 3u, 7u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    CurveProblemOptions problem;
    problem.seed = seed;
    const CurveSamples clean = MakeCurveSamples(problem);
    problem.outlier_fraction = 0.1;
    const CurveSamples dirty = MakeCurveSamples(problem);
    Eigen::Matrix3d cov;
    ASSERT_TRUE(CurveCovariance(
        clean, FitWithLm(clean, LmOptions{}).p.head<3>(), &cov));

    for (const RobustKernel& kernel :
         {RobustKernel{KernelType::kNone, 1.0},
          RobustKernel{KernelType::kHuber, kHuber95Scale * problem.sigma},
          RobustKernel{KernelType::kCauchy, kCauchy95Scale * problem.sigma}}) {
      SCOPED_TRACE(KernelTypeName(kernel.type));
      LmOptions lm_options;
      lm_options.kernel = kernel;
      const Eigen::Vector3d lm = FitWithLm(dirty, lm_options).p.head<3>();
      CeresFitOptions ceres_options;
      ceres_options.kernel = kernel;
      const CeresFitResult ceres =
          FitCurveWithCeres(dirty, Eigen::Vector3d::Zero(), ceres_options);
      EXPECT_LT(MaxRelativeDifference(lm, ceres.p), 1e-6);
      if (kernel.type == KernelType::kNone) {
        EXPECT_GT(Mahalanobis2(lm, cov), kFar);
        EXPECT_GT(Mahalanobis2(ceres.p, cov), kFar);
      } else {
        EXPECT_LT(Mahalanobis2(lm, cov), kNear);
        EXPECT_LT(Mahalanobis2(ceres.p, cov), kNear);
      }
    }
  }
}

TEST(CurveProblem, SamplesAreDeterministicAndOutliersCounted) {
  CurveProblemOptions options;
  options.outlier_fraction = 0.1;
  const CurveSamples a = MakeCurveSamples(options);
  const CurveSamples b = MakeCurveSamples(options);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(std::count(a.is_outlier.begin(), a.is_outlier.end(), true), 10);
  EXPECT_DOUBLE_EQ(a.x[50], 0.5);
  for (size_t i = 0; i < a.x.size(); ++i) {
    if (a.is_outlier[i]) {
      EXPECT_GT(a.y[i] - CurveModel(kTruth, a.x[i]), 5.0);
    }
  }
  options.num_samples = 2;
  EXPECT_THROW(MakeCurveSamples(options), std::invalid_argument);
}

// Runs the tool with a shell, returning its exit status and its stdout and
// stderr together.
int RunTool(const std::string& arguments, std::string* output) {
  const std::string command =
      std::string(VIO_CURVE_FITTING_TOOL) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return -1;
  char buffer[4096];
  output->clear();
  while (fgets(buffer, sizeof(buffer), pipe) != nullptr) *output += buffer;
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(CurveFittingTool, RunsTheExerciseAndWritesAReadablePlot) {
  const std::string png = "curve_fitting_tool_test.png";
  std::remove(png.c_str());
  std::string output;
  ASSERT_EQ(RunTool("--outliers 0.1 --kernel huber --plot " + png, &output), 0)
      << output;
  EXPECT_NE(output.find("Ceres Solver Report"), std::string::npos) << output;
  EXPECT_NE(output.find("iter: 0 , chi2="), std::string::npos) << output;
  EXPECT_NE(output.find("hand LM "), std::string::npos) << output;
  EXPECT_NE(output.find("wrote " + png), std::string::npos) << output;
  const cv::Mat image = cv::imread(png);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 1000);
  EXPECT_EQ(image.rows, 650);
  // Something was drawn: not every pixel is white.
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(grey < 200), 1000);
}

TEST(CurveFittingTool, BadOptionsGiveAnErrorAndExitStatusOne) {
  std::string output;
  EXPECT_EQ(RunTool("--n 2", &output), 1);
  EXPECT_NE(output.find("error: num_samples must be >= 3"), std::string::npos)
      << output;
  EXPECT_EQ(RunTool("--damping fast", &output), 1);
  EXPECT_NE(output.find("error: --damping expects"), std::string::npos)
      << output;
  EXPECT_EQ(RunTool("--sigma", &output), 1);
  EXPECT_NE(output.find("error: --sigma needs a value"), std::string::npos);
  EXPECT_EQ(RunTool("--plot /nonexistent-dir/x.png", &output), 1);
  EXPECT_NE(output.find("error: /nonexistent-dir/x.png"), std::string::npos)
      << output;
  EXPECT_EQ(RunTool("--help", &output), 0);
  EXPECT_NE(output.find("usage: curve_fitting"), std::string::npos);
}

}  // namespace
}  // namespace vio
