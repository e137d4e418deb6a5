#ifndef VIO_NAVIGATION_WHITE_ACCELERATION_MODEL_H_
#define VIO_NAVIGATION_WHITE_ACCELERATION_MODEL_H_

// The motion model of the user's notes: each axis has a state (position,
// rate) that moves at constant rate between stamps, driven by an acceleration
// that is white noise held over each step of length T:
//
//   x_t = A x_{t-1} + G a,   A = [1 T; 0 1],   G = [T^2/2; T],
//   a ~ N(0, k^2)   =>   R_t = k^2 G G^T = k^2 [T^4/4  T^3/2; T^3/2  T^2].
//
// (Bar-Shalom calls it the discrete white noise acceleration model; the issue
// calls it the constant-acceleration model of the notes.) Several axes stack
// block-diagonally in the notes' interleaved order: for the planar state
// (X, Xdot, Z, Zdot, theta, thetadot) with noises k1, k2, k3,
// ProcessNoise(T, {k1, k2, k3}) is the notes' R_t, except its last entry: the
// notes write T^2 k2^2 where the theta-rate variance is T^2 k3^2 (with k2 !=
// k3 the notes' matrix is not even positive semi-definite; see
// docs/navigation.md).

#include <Eigen/Core>
#include <vector>

namespace vio {

// A of one axis: [1 T; 0 1]. T [s].
Eigen::Matrix2d AxisTransition(double T);

// R_t of one axis: k^2 [T^4/4 T^3/2; T^3/2 T^2]. T [s], k [unit/s^2].
Eigen::Matrix2d AxisProcessNoise(double T, double k);

// Block-diagonal A of k.size() axes (state: p0, rate0, p1, rate1, ...).
Eigen::MatrixXd Transition(int axes, double T);

// Block-diagonal R_t, one block per entry of k. Throws std::invalid_argument
// when T < 0 or a k is negative or non-finite.
Eigen::MatrixXd ProcessNoise(double T, const std::vector<double>& k);

}  // namespace vio

#endif  // VIO_NAVIGATION_WHITE_ACCELERATION_MODEL_H_
