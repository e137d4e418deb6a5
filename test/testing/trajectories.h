#ifndef VIO_TEST_TESTING_TRAJECTORIES_H_
#define VIO_TEST_TESTING_TRAJECTORIES_H_

// Trajectories and similarity transforms for the eval tests.

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "dataset/trajectory.h"

namespace vio::testing {

// A similarity p_w = scale * R_w_e * p_e + t_w_e (the alignment convention).
struct Similarity {
  Eigen::Matrix3d R_w_e = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_w_e = Eigen::Vector3d::Zero();  // [m]
  double scale = 1.0;

  StampedPose Apply(const StampedPose& p) const {
    StampedPose out = p;
    out.p_w_b = scale * (R_w_e * p.p_w_b) + t_w_e;
    out.q_w_b = Eigen::Quaterniond(R_w_e) * p.q_w_b;
    return out;
  }
  Similarity Inverse() const {
    return {R_w_e.transpose(), -(R_w_e.transpose() * t_w_e) / scale,
            1.0 / scale};
  }
};

inline Trajectory Transform(const Similarity& S, const Trajectory& in) {
  Trajectory out;
  for (const StampedPose& p : in) out.push_back(S.Apply(p));
  return out;
}

inline Eigen::Matrix3d RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng))
      .normalized()
      .toRotationMatrix();
}

inline Eigen::Matrix3d Yaw(double yaw_rad) {
  return Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).matrix();
}

// A drone-like loop: a 3D Lissajous curve a few metres across with the body
// turning along it, `count` poses every `dt_ns`.
inline Trajectory Lissajous(int count, int64_t dt_ns = 50000000,
                            int64_t t0_ns = 1000000000) {
  Trajectory t;
  for (int i = 0; i < count; ++i) {
    const double s = 0.05 * i;
    StampedPose p;
    p.t_ns = t0_ns + i * dt_ns;
    p.p_w_b = {4.0 * std::sin(s), 2.5 * std::sin(2.0 * s + 0.3),
               1.0 + 0.5 * std::cos(0.7 * s)};
    p.q_w_b = Eigen::AngleAxisd(s, Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(0.2 * std::sin(s), Eigen::Vector3d::UnitX());
    t.push_back(p);
  }
  return t;
}

inline Trajectory AddPositionNoise(const Trajectory& in, double sigma_m,
                                   std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, sigma_m);
  Trajectory out = in;
  for (StampedPose& p : out) p.p_w_b += Eigen::Vector3d(n(rng), n(rng), n(rng));
  return out;
}

// Angle between two rotations [rad].
inline double AngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

}  // namespace vio::testing

#endif  // VIO_TEST_TESTING_TRAJECTORIES_H_
