#include "estimator/visual_inertial_alignment.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <cmath>

#include "geometry/so3.h"

namespace vio {
namespace {

// r_k = Log(dq_k^-1 R_k^T R_{k+1}) at the interval's linearisation bias.
Eigen::Vector3d RotationMisfit(const AlignmentFrame& i, const AlignmentFrame& j,
                               const ImuPreintegration& interval) {
  const Eigen::Quaterniond q_vis(i.R_v_b.transpose() * j.R_v_b);
  return Log(interval.delta().q.conjugate() * q_vis.normalized());
}

// Column of the unknown vector: v_k at 3k, then g (3), then s.
int GravityColumn(int frames) { return 3 * frames; }
int ScaleColumn(int frames) { return 3 * frames + 3; }

// The stacked system A x = b of the header (6 rows per interval), with the
// scale column only when estimate_scale; otherwise s = 1 is moved to b.
void BuildSystem(const std::vector<AlignmentFrame>& frames,
                 const std::vector<ImuPreintegration>& intervals,
                 const Eigen::Vector3d& t_b_c, const Eigen::Vector3d& b_a,
                 bool estimate_scale, Eigen::MatrixXd* A, Eigen::VectorXd* b) {
  const int n = static_cast<int>(frames.size());
  const int cols = 3 * n + 3 + (estimate_scale ? 1 : 0);
  *A = Eigen::MatrixXd::Zero(6 * (n - 1), cols);
  *b = Eigen::VectorXd::Zero(6 * (n - 1));
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (int k = 0; k + 1 < n; ++k) {
    const AlignmentFrame& fi = frames[k];
    const AlignmentFrame& fj = frames[k + 1];
    const ImuPreintegration& imu = intervals[k];
    const double T = imu.sum_dt();
    // The bias-corrected terms at (b_a, the interval's gyroscope bias).
    const ImuDelta d = imu.Corrected(b_a, imu.lin_b_g());
    const Eigen::Vector3d dpbar = fj.p_v_c - fi.p_v_c;
    const int rp = 6 * k, rv = 6 * k + 3;
    // Position: s dpbar - T v_k - T^2/2 g = R_k dp + (R_{k+1} - R_k) t_b_c.
    A->block<3, 3>(rp, 3 * k) = -T * I;
    A->block<3, 3>(rp, GravityColumn(n)) = -0.5 * T * T * I;
    b->segment<3>(rp) = fi.R_v_b * d.p + (fj.R_v_b - fi.R_v_b) * t_b_c;
    if (estimate_scale) {
      A->block<3, 1>(rp, ScaleColumn(n)) = dpbar;
    } else {
      b->segment<3>(rp) -= dpbar;
    }
    // Velocity: v_{k+1} - v_k - T g = R_k dv.
    A->block<3, 3>(rv, 3 * k) = -I;
    A->block<3, 3>(rv, 3 * (k + 1)) = I;
    A->block<3, 3>(rv, GravityColumn(n)) = -T * I;
    b->segment<3>(rv) = fi.R_v_b * d.v;
  }
}

// Least squares with column scaling (the scale's column is in visual units,
// the others in seconds); fills x, the residual RMS and sigma^2 (A^T A)^-1's
// diagonal entry of column `col` (negative col: not wanted).
bool SolveScaled(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int col,
                 Eigen::VectorXd* x, double* residual_rms, double* sigma_col) {
  const Eigen::VectorXd norms = A.colwise().norm();
  if ((norms.array() <= 0.0).any()) return false;
  const Eigen::MatrixXd As = A * norms.cwiseInverse().asDiagonal();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(As);
  if (qr.rank() < As.cols()) return false;
  const Eigen::VectorXd y = qr.solve(b);
  *x = norms.cwiseInverse().asDiagonal() * y;
  const Eigen::VectorXd r = A * *x - b;
  *residual_rms =
      std::sqrt(r.squaredNorm() / std::max<Eigen::Index>(1, r.size()));
  if (col >= 0) {
    const Eigen::Index dof = A.rows() - A.cols();
    const double sigma2 = dof > 0 ? r.squaredNorm() / dof : 0.0;
    const Eigen::MatrixXd info = As.transpose() * As;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(As.cols());
    e[col] = 1.0;
    const double cov_scaled = info.ldlt().solve(e)[col];
    *sigma_col = std::sqrt(std::max(0.0, sigma2 * cov_scaled)) / norms[col];
  }
  return x->allFinite();
}

// Two unit vectors spanning the plane orthogonal to the unit vector g_hat.
Eigen::Matrix<double, 3, 2> TangentBasis(const Eigen::Vector3d& g_hat) {
  const Eigen::Vector3d helper = std::abs(g_hat.z()) < 0.9
                                     ? Eigen::Vector3d::UnitZ()
                                     : Eigen::Vector3d::UnitX();
  Eigen::Matrix<double, 3, 2> B;
  B.col(0) = g_hat.cross(helper).normalized();
  B.col(1) = g_hat.cross(B.col(0)).normalized();
  return B;
}

void Unpack(const Eigen::VectorXd& x, int n, VelocityGravityScale* result) {
  result->v_v.resize(n);
  for (int k = 0; k < n; ++k) result->v_v[k] = x.segment<3>(3 * k);
}

}  // namespace

double RotationMisfitRms(const std::vector<AlignmentFrame>& frames,
                         const std::vector<ImuPreintegration>& intervals) {
  double sum = 0.0;
  for (size_t k = 0; k + 1 < frames.size(); ++k) {
    sum += RotationMisfit(frames[k], frames[k + 1], intervals[k]).squaredNorm();
  }
  return frames.size() < 2 ? 0.0 : std::sqrt(sum / (frames.size() - 1));
}

Eigen::Vector3d AlignGyroscopeBias(const std::vector<AlignmentFrame>& frames,
                                   const Eigen::Vector3d& b_a,
                                   std::vector<ImuPreintegration>* intervals,
                                   int iterations) {
  Eigen::Vector3d b_g = intervals->empty() ? Eigen::Vector3d::Zero()
                                           : intervals->front().lin_b_g();
  for (int it = 0; it < iterations; ++it) {
    // Log(Exp(-J d) dq^-1 R_vis) ~ r - J d for a small misfit r (the left
    // Jacobian of Log at r is ~ I), so the normal equations are
    // (sum J^T J) d = sum J^T r.
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (size_t k = 0; k + 1 < frames.size(); ++k) {
      const ImuPreintegration& imu = (*intervals)[k];
      const Eigen::Matrix3d& J = imu.result().d_dq_d_bg;
      H += J.transpose() * J;
      g += J.transpose() * RotationMisfit(frames[k], frames[k + 1], imu);
    }
    const Eigen::Vector3d d = H.ldlt().solve(g);
    if (!d.allFinite()) break;
    b_g += d;
    for (ImuPreintegration& imu : *intervals) imu.Repropagate(b_a, b_g);
  }
  return b_g;
}

bool SolveVelocityGravityScale(const std::vector<AlignmentFrame>& frames,
                               const std::vector<ImuPreintegration>& intervals,
                               const Eigen::Vector3d& t_b_c,
                               const Eigen::Vector3d& b_a, bool estimate_scale,
                               VelocityGravityScale* result) {
  const int n = static_cast<int>(frames.size());
  if (n < 2 || static_cast<int>(intervals.size()) < n - 1) return false;
  Eigen::MatrixXd A;
  Eigen::VectorXd b, x;
  BuildSystem(frames, intervals, t_b_c, b_a, estimate_scale, &A, &b);
  double sigma = 0.0;
  if (!SolveScaled(A, b, estimate_scale ? ScaleColumn(n) : -1, &x,
                   &result->residual_rms, &sigma)) {
    return false;
  }
  Unpack(x, n, result);
  result->g_v = x.segment<3>(GravityColumn(n));
  result->scale = estimate_scale ? x[ScaleColumn(n)] : 1.0;
  result->scale_sigma = estimate_scale ? sigma : 0.0;
  return true;
}

bool RefineGravity(const std::vector<AlignmentFrame>& frames,
                   const std::vector<ImuPreintegration>& intervals,
                   const Eigen::Vector3d& t_b_c, const Eigen::Vector3d& b_a,
                   double gravity_magnitude, bool estimate_scale,
                   VelocityGravityScale* result, int iterations) {
  const int n = static_cast<int>(frames.size());
  if (n < 2 || result->g_v.norm() <= 0.0) return false;
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  BuildSystem(frames, intervals, t_b_c, b_a, estimate_scale, &A, &b);
  Eigen::Vector3d g_hat = result->g_v.normalized();
  for (int it = 0; it < iterations; ++it) {
    // A_g g = A_g (G g_hat) + (A_g B) w: the first term moves to b, the
    // gravity columns become the two of w.
    const Eigen::Matrix<double, 3, 2> B = TangentBasis(g_hat);
    const Eigen::MatrixXd A_g = A.middleCols<3>(GravityColumn(n));
    Eigen::MatrixXd Ar(A.rows(), A.cols() - 1);
    Ar.leftCols(3 * n) = A.leftCols(3 * n);
    Ar.middleCols<2>(3 * n) = A_g * B;
    if (estimate_scale) Ar.rightCols<1>() = A.rightCols<1>();
    const Eigen::VectorXd br = b - A_g * (gravity_magnitude * g_hat);
    Eigen::VectorXd x;
    double sigma = 0.0;
    if (!SolveScaled(Ar, br, estimate_scale ? 3 * n + 2 : -1, &x,
                     &result->residual_rms, &sigma)) {
      return false;
    }
    g_hat = (gravity_magnitude * g_hat + B * x.segment<2>(3 * n)).normalized();
    Unpack(x, n, result);
    result->scale = estimate_scale ? x[3 * n + 2] : 1.0;
    result->scale_sigma = estimate_scale ? sigma : 0.0;
  }
  result->g_v = gravity_magnitude * g_hat;
  return true;
}

Eigen::Matrix3d GravityAlignedRotation(const Eigen::Vector3d& g_v) {
  return Eigen::Quaterniond::FromTwoVectors(g_v, -Eigen::Vector3d::UnitZ())
      .toRotationMatrix();
}

}  // namespace vio
