#ifndef VIO_TEST_TESTING_IMU_RESIDUAL_FUNCTOR_H_
#define VIO_TEST_TESTING_IMU_RESIDUAL_FUNCTOR_H_

// The IMU factor's weighted residual (factors/imu_factor.h) written once more
// as a templated functor, for ceres::AutoDiffCostFunction: a third opinion on
// the analytic Jacobians (tests) and the baseline of the benchmark. It
// repeats the math independently, with Ceres' own rotation helpers
// (AngleAxisToQuaternion for Exp, QuaternionToAngleAxis for Log).

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "preintegration/imu_preintegration.h"

namespace vio {
namespace testing {

class ImuResidualFunctor {
 public:
  ImuResidualFunctor(const PreintegratedImu& pre, double gravity_magnitude,
                     const Matrix15d& sqrt_information)
      : pre_(pre),
        g_w_(0.0, 0.0, -gravity_magnitude),
        sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* pose_i, const T* speed_bias_i, const T* pose_j,
                  const T* speed_bias_j, T* residuals) const {
    using Vec3 = Eigen::Matrix<T, 3, 1>;
    using Quat = Eigen::Quaternion<T>;
    const Eigen::Map<const Vec3> p_i(pose_i), p_j(pose_j);
    const Eigen::Map<const Quat> q_i(pose_i + 3), q_j(pose_j + 3);
    const Eigen::Map<const Vec3> v_i(speed_bias_i), v_j(speed_bias_j);
    const Eigen::Map<const Vec3> b_a_i(speed_bias_i + 3),
        b_a_j(speed_bias_j + 3);
    const Eigen::Map<const Vec3> b_g_i(speed_bias_i + 6),
        b_g_j(speed_bias_j + 6);

    const Vec3 db_a = b_a_i - pre_.lin_b_a.cast<T>();
    const Vec3 db_g = b_g_i - pre_.lin_b_g.cast<T>();
    const Vec3 dp = pre_.delta.p.cast<T>() + pre_.d_dp_d_ba.cast<T>() * db_a +
                    pre_.d_dp_d_bg.cast<T>() * db_g;
    const Vec3 dv = pre_.delta.v.cast<T>() + pre_.d_dv_d_ba.cast<T>() * db_a +
                    pre_.d_dv_d_bg.cast<T>() * db_g;
    const Vec3 phi = pre_.d_dq_d_bg.cast<T>() * db_g;
    T corr_wxyz[4];
    ceres::AngleAxisToQuaternion(phi.data(), corr_wxyz);
    const Quat dq = pre_.delta.q.cast<T>() * Quat(corr_wxyz[0], corr_wxyz[1],
                                                  corr_wxyz[2], corr_wxyz[3]);
    const Quat q_err = dq.conjugate() * q_i.conjugate() * q_j;
    const T err_wxyz[4] = {q_err.w(), q_err.x(), q_err.y(), q_err.z()};

    const T T_ij = T(pre_.sum_dt);
    const Vec3 g = g_w_.cast<T>();
    Eigen::Matrix<T, 15, 1> r;
    r.template segment<3>(kImuP) =
        q_i.conjugate() * (p_j - p_i - v_i * T_ij - T(0.5) * g * T_ij * T_ij) -
        dp;
    ceres::QuaternionToAngleAxis(err_wxyz, r.data() + kImuR);
    r.template segment<3>(kImuV) =
        q_i.conjugate() * (v_j - v_i - g * T_ij) - dv;
    r.template segment<3>(kImuBa) = b_a_j - b_a_i;
    r.template segment<3>(kImuBg) = b_g_j - b_g_i;
    Eigen::Map<Eigen::Matrix<T, 15, 1>> weighted(residuals);
    weighted = sqrt_information_.cast<T>() * r;
    return true;
  }

 private:
  PreintegratedImu pre_;
  Eigen::Vector3d g_w_;
  Matrix15d sqrt_information_;
};

using ImuAutoDiffCost =
    ceres::AutoDiffCostFunction<ImuResidualFunctor, 15, 7, 9, 7, 9>;

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_IMU_RESIDUAL_FUNCTOR_H_
