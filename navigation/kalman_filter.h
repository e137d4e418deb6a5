#ifndef VIO_NAVIGATION_KALMAN_FILTER_H_
#define VIO_NAVIGATION_KALMAN_FILTER_H_

// The linear Kalman filter of the user's notes (Algorithm 2), for any state
// and measurement sizes:
//
//   predict   mu_bar    = A mu
//             Sigma_bar = A Sigma A^T + R_t
//   update    K         = Sigma_bar H^T (H Sigma_bar H^T + Q_t)^-1
//             mu        = mu_bar + K (z - H mu_bar)
//             Sigma     = (E - K H) Sigma_bar (E - K H)^T + K Q_t K^T
//
// The names follow the notes (and Thrun, Burgard and Fox, "Probabilistic
// Robotics", table 3.1): R_t is the PROCESS noise, Q_t the MEASUREMENT noise,
// E the identity. The notes measure the whole state (H = E); Update(z, Q)
// is that special case of Update(z, H, Q).
//
// Two changes from the notes, both of which leave the optimal result equal:
//   - the covariance update is Joseph's form. With the optimal gain it equals
//     the notes' (E - K H) Sigma_bar exactly, but it stays symmetric and
//     positive semi-definite under rounding and for any gain;
//   - measurement rows that are angles have their innovation z - H mu_bar
//     wrapped to (-pi, pi], so a yaw measured as +179 deg against a
//     prediction of -179 deg is a 2 deg innovation, not 358 deg.

#include <Eigen/Core>
#include <vector>

namespace vio {

// An angle [rad] wrapped to (-pi, pi].
double WrapToPi(double angle_rad);

// What one update did (for consistency checks: NIS, innovation whiteness).
struct KalmanUpdateInfo {
  Eigen::VectorXd innovation;  // z - H mu_bar, angle rows wrapped
  Eigen::MatrixXd S;           // innovation covariance H Sigma_bar H^T + Q
  Eigen::MatrixXd K;           // gain
  double nis = 0.0;            // innovation^T S^-1 innovation [-]
};

class KalmanFilter {
 public:
  // The state's mean and covariance; throws std::invalid_argument unless
  // sigma is square, of mu's size, symmetric and finite.
  KalmanFilter(const Eigen::VectorXd& mu, const Eigen::MatrixXd& sigma);

  // mu <- A mu, Sigma <- A Sigma A^T + R. Throws std::invalid_argument on
  // sizes that do not fit the state.
  void Predict(const Eigen::MatrixXd& A, const Eigen::MatrixXd& R);

  // The general update with z = H x + v, v ~ N(0, Q). angle_rows lists the
  // rows of z whose innovation is wrapped to (-pi, pi]. Throws
  // std::invalid_argument on sizes that do not fit, or when S is not
  // positive definite.
  KalmanUpdateInfo Update(const Eigen::VectorXd& z, const Eigen::MatrixXd& H,
                          const Eigen::MatrixXd& Q,
                          const std::vector<int>& angle_rows = {});

  // The notes' update: the whole state measured (H = E).
  KalmanUpdateInfo Update(const Eigen::VectorXd& z, const Eigen::MatrixXd& Q);

  const Eigen::VectorXd& mean() const { return mu_; }
  const Eigen::MatrixXd& covariance() const { return sigma_; }
  // Replaces one entry of the mean (e.g. to wrap an angle state).
  void SetMean(int row, double value) { mu_(row) = value; }

 private:
  Eigen::VectorXd mu_;
  Eigen::MatrixXd sigma_;
};

}  // namespace vio

#endif  // VIO_NAVIGATION_KALMAN_FILTER_H_
