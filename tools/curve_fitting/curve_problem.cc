#include "tools/curve_fitting/curve_problem.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

namespace vio {

namespace {

// A value as text for error messages: "1.5", not "1.500000".
std::string FormatValue(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

bool CurveProblemOptions::Validate(std::string* message) const {
  auto fail = [message](const std::string& text) {
    *message = text;
    return false;
  };
  if (!truth.allFinite()) return fail("truth (a, b, c) must be finite");
  if (num_samples < 3) {
    return fail("num_samples must be >= 3 (got " + std::to_string(num_samples) +
                ")");
  }
  if (!(std::isfinite(sigma) && sigma >= 0.0)) {
    return fail("sigma must be finite and >= 0 (got " + FormatValue(sigma) +
                ")");
  }
  if (!(outlier_fraction >= 0.0 && outlier_fraction <= 1.0)) {
    return fail("outlier_fraction must be in [0, 1] (got " +
                FormatValue(outlier_fraction) + ")");
  }
  if (!(std::isfinite(outlier_max_sigmas) && outlier_min_sigmas >= 0.0 &&
        outlier_min_sigmas <= outlier_max_sigmas)) {
    return fail("outlier sizes must satisfy 0 <= min <= max");
  }
  return true;
}

double CurveModel(const Eigen::Vector3d& p, double x) {
  return std::exp(p[kCurveA] * x * x + p[kCurveB] * x + p[kCurveC]);
}

CurveSamples MakeCurveSamples(const CurveProblemOptions& options) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("CurveProblemOptions: " + message);
  }
  const int n = options.num_samples;
  std::mt19937 rng(options.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  CurveSamples samples;
  samples.x.resize(n);
  samples.y.resize(n);
  samples.is_outlier.assign(n, false);
  for (int i = 0; i < n; ++i) {
    samples.x[i] = static_cast<double>(i) / n;
    samples.y[i] =
        CurveModel(options.truth, samples.x[i]) + options.sigma * noise(rng);
  }
  // The outliers: a random subset (a shuffle of the indices, same rng).
  const int num_outliers = static_cast<int>(options.outlier_fraction * n);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  std::uniform_real_distribution<double> size(options.outlier_min_sigmas,
                                              options.outlier_max_sigmas);
  for (int j = 0; j < num_outliers; ++j) {
    const int i = order[j];
    samples.y[i] += size(rng) * options.sigma;
    samples.is_outlier[i] = true;
  }
  return samples;
}

ResidualFunction CurveResiduals(const CurveSamples& samples) {
  return [&samples](const Eigen::VectorXd& p, Eigen::VectorXd* r,
                    Eigen::MatrixXd* d_r_d_p) {
    const Eigen::Index n = static_cast<Eigen::Index>(samples.x.size());
    r->resize(n);
    d_r_d_p->resize(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double x = samples.x[i];
      const double e = CurveModel(p.head<3>(), x);
      if (!std::isfinite(e)) return false;
      (*r)[i] = e - samples.y[i];
      // d exp(u) / d p = exp(u) d u / d p, u = a x^2 + b x + c.
      d_r_d_p->row(i) << e * x * x, e * x, e;
    }
    return true;
  };
}

bool CurveCovariance(const CurveSamples& samples, const Eigen::Vector3d& p,
                     Eigen::Matrix3d* covariance) {
  Eigen::VectorXd r;
  Eigen::MatrixXd d_r_d_p;
  const Eigen::VectorXd p_dynamic = p;
  if (!CurveResiduals(samples)(p_dynamic, &r, &d_r_d_p)) return false;
  const Eigen::Matrix3d information = d_r_d_p.transpose() * d_r_d_p;
  const Eigen::LLT<Eigen::Matrix3d> llt(information);
  if (llt.info() != Eigen::Success) return false;
  const double s2 = r.squaredNorm() / static_cast<double>(r.size() - 3);
  *covariance = llt.solve(Eigen::Matrix3d::Identity()) * s2;
  return covariance->allFinite();
}

}  // namespace vio
