#include "navigation/kalman_filter.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

void Require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("KalmanFilter: " + message);
}

std::string Size(const Eigen::MatrixXd& m) {
  return std::to_string(m.rows()) + "x" + std::to_string(m.cols());
}

}  // namespace

double WrapToPi(double angle_rad) {
  // remainder() maps to [-pi, pi]; -pi is moved to +pi for (-pi, pi].
  const double wrapped = std::remainder(angle_rad, 2.0 * M_PI);
  return wrapped <= -M_PI ? wrapped + 2.0 * M_PI : wrapped;
}

KalmanFilter::KalmanFilter(const Eigen::VectorXd& mu,
                           const Eigen::MatrixXd& sigma)
    : mu_(mu), sigma_(sigma) {
  const Eigen::Index n = mu.size();
  Require(n > 0, "the state is empty");
  Require(sigma.rows() == n && sigma.cols() == n,
          "Sigma is " + Size(sigma) + " for a state of " + std::to_string(n));
  Require(mu.allFinite() && sigma.allFinite(), "non-finite mean or Sigma");
  Require((sigma - sigma.transpose()).cwiseAbs().maxCoeff() <=
              1e-9 * (1.0 + sigma.cwiseAbs().maxCoeff()),
          "Sigma is not symmetric");
}

void KalmanFilter::Predict(const Eigen::MatrixXd& A, const Eigen::MatrixXd& R) {
  const Eigen::Index n = mu_.size();
  Require(A.rows() == n && A.cols() == n, "A is " + Size(A));
  Require(R.rows() == n && R.cols() == n, "R_t is " + Size(R));
  mu_ = A * mu_;
  sigma_ = A * sigma_ * A.transpose() + R;
  sigma_ = 0.5 * (sigma_ + sigma_.transpose());
}

KalmanUpdateInfo KalmanFilter::Update(const Eigen::VectorXd& z,
                                      const Eigen::MatrixXd& H,
                                      const Eigen::MatrixXd& Q,
                                      const std::vector<int>& angle_rows) {
  const Eigen::Index n = mu_.size();
  const Eigen::Index m = z.size();
  Require(H.rows() == m && H.cols() == n, "H is " + Size(H));
  Require(Q.rows() == m && Q.cols() == m, "Q_t is " + Size(Q));
  Require(z.allFinite(), "non-finite measurement");
  KalmanUpdateInfo info;
  info.innovation = z - H * mu_;
  for (int row : angle_rows) {
    Require(row >= 0 && row < m, "angle row out of range");
    info.innovation(row) = WrapToPi(info.innovation(row));
  }
  info.S = H * sigma_ * H.transpose() + Q;
  const Eigen::LDLT<Eigen::MatrixXd> S_ldlt(info.S);
  Require(S_ldlt.info() == Eigen::Success && S_ldlt.isPositive() &&
              (S_ldlt.vectorD().array() > 0.0).all(),
          "the innovation covariance is not positive definite");
  // K = Sigma_bar H^T S^-1 = (S^-1 H Sigma_bar)^T, both factors symmetric.
  info.K = S_ldlt.solve(H * sigma_).transpose();
  info.nis = info.innovation.dot(S_ldlt.solve(info.innovation));
  mu_ += info.K * info.innovation;
  // Joseph form: (E - K H) Sigma_bar (E - K H)^T + K Q K^T.
  const Eigen::MatrixXd I_KH = Eigen::MatrixXd::Identity(n, n) - info.K * H;
  sigma_ = I_KH * sigma_ * I_KH.transpose() + info.K * Q * info.K.transpose();
  sigma_ = 0.5 * (sigma_ + sigma_.transpose());
  return info;
}

KalmanUpdateInfo KalmanFilter::Update(const Eigen::VectorXd& z,
                                      const Eigen::MatrixXd& Q) {
  return Update(z, Eigen::MatrixXd::Identity(mu_.size(), mu_.size()), Q);
}

}  // namespace vio
