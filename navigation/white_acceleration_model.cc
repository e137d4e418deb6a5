#include "navigation/white_acceleration_model.h"

#include <cmath>
#include <stdexcept>

namespace vio {

Eigen::Matrix2d AxisTransition(double T) {
  Eigen::Matrix2d A;
  A << 1.0, T, 0.0, 1.0;
  return A;
}

Eigen::Matrix2d AxisProcessNoise(double T, double k) {
  // Cov(G a) = G Var(a) G^T with G = (T^2/2, T): the position moves by
  // a T^2 / 2 and the rate by a T under an acceleration a held over T.
  const Eigen::Vector2d G(0.5 * T * T, T);
  return k * k * G * G.transpose();
}

Eigen::MatrixXd Transition(int axes, double T) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * axes, 2 * axes);
  for (int i = 0; i < axes; ++i)
    A.block<2, 2>(2 * i, 2 * i) = AxisTransition(T);
  return A;
}

Eigen::MatrixXd ProcessNoise(double T, const std::vector<double>& k) {
  if (!(T >= 0.0) || !std::isfinite(T)) {
    throw std::invalid_argument("ProcessNoise: T must be >= 0 [s]");
  }
  const int axes = static_cast<int>(k.size());
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(2 * axes, 2 * axes);
  for (int i = 0; i < axes; ++i) {
    if (!(k[i] >= 0.0) || !std::isfinite(k[i])) {
      throw std::invalid_argument(
          "ProcessNoise: every acceleration noise must be >= 0");
    }
    R.block<2, 2>(2 * i, 2 * i) = AxisProcessNoise(T, k[i]);
  }
  return R;
}

}  // namespace vio
