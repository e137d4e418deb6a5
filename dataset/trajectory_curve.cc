#include "dataset/trajectory_curve.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "geometry/so3.h"

namespace vio {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

struct Sample {
  double t;  // seconds after the first sample
  Eigen::Vector3d p;
  Eigen::Quaterniond q;
};

void AddBlock(int row, int col, const Eigen::MatrixXd& m, Triplets* h) {
  for (int r = 0; r < m.rows(); ++r) {
    for (int c = 0; c < m.cols(); ++c) {
      h->emplace_back(row + r, col + c, m(r, c));
    }
  }
}

Eigen::SparseMatrix<double> Assemble(int n, const Triplets& triplets) {
  Eigen::SparseMatrix<double> h(n, n);
  h.setFromTriplets(triplets.begin(), triplets.end());  // sums duplicates
  return h;
}

Eigen::MatrixXd Solve(const Eigen::SparseMatrix<double>& h,
                      const Eigen::MatrixXd& rhs) {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(h);
  if (ldlt.info() != Eigen::Success) {
    throw std::invalid_argument(
        "TrajectoryCurve: the fit's normal equations are singular");
  }
  return ldlt.solve(rhs);
}

// Control positions: a linear least-squares problem, one solve for x, y, z.
std::vector<Eigen::Vector3d> FitPositions(const std::vector<Sample>& samples,
                                          int n, const CurveFitOptions& o) {
  const double dt = o.knot_spacing_s;
  const double w_data = 1.0 / (o.position_sigma_m * o.position_sigma_m);
  const double s_acc = o.acceleration_sigma * dt * dt;
  const double w_smooth = 1.0 / (s_acc * s_acc);
  Triplets h;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
  const PoseSpline layout(0.0, dt, std::vector<Eigen::Vector3d>(n),
                          std::vector<Eigen::Quaterniond>(n));
  // Summed per segment first: one 4x4 block per segment, not per sample.
  std::vector<Eigen::Matrix4d> segment(n - 3, Eigen::Matrix4d::Zero());
  for (const Sample& s : samples) {
    double u = 0.0;
    const int i = layout.Segment(s.t, &u);
    const Eigen::Vector4d b = PoseSpline::Basis(u, 0);
    segment[i] += w_data * b * b.transpose();
    for (int k = 0; k < 4; ++k) {
      rhs.row(i + k) += w_data * b[k] * s.p.transpose();
    }
  }
  for (int i = 0; i + 3 < n; ++i) AddBlock(i, i, segment[i], &h);
  // Second differences c_{k-1} - 2 c_k + c_{k+1} ~ acceleration dt^2.
  const Eigen::Vector3d second(1.0, -2.0, 1.0);
  for (int k = 1; k + 1 < n; ++k) {
    AddBlock(k - 1, k - 1, w_smooth * second * second.transpose(), &h);
  }
  const Eigen::MatrixXd c = Solve(Assemble(n, h), rhs);
  std::vector<Eigen::Vector3d> positions(n);
  for (int k = 0; k < n; ++k) positions[k] = c.row(k).transpose();
  return positions;
}

// The sampled rotation at t (slerp between the samples around it).
Eigen::Quaterniond Interpolate(const std::vector<Sample>& samples, double t) {
  if (t <= samples.front().t) return samples.front().q;
  if (t >= samples.back().t) return samples.back().q;
  const auto after =
      std::upper_bound(samples.begin(), samples.end(), t,
                       [](double x, const Sample& s) { return x < s.t; });
  const Sample& a = *(after - 1);
  const Sample& b = *after;
  return a.q.slerp((t - a.t) / (b.t - a.t), b.q);
}

// d_i = Log(R_i^T R_{i+1}) and its Jacobians on right perturbations of R_i
// (-Jr^-1(d) Exp(d)^T, since Exp(-e) M = M Exp(-M^T e)) and R_{i+1}
// (Jr^-1(d)).
struct Increment {
  Eigen::Vector3d d;
  Eigen::Matrix3d d_d_d_first, d_d_d_second;
};

Increment IncrementOf(const Eigen::Quaterniond& a,
                      const Eigen::Quaterniond& b) {
  Increment inc;
  inc.d = Log(a.conjugate() * b);
  inc.d_d_d_second = RightJacobianInverse(inc.d);
  inc.d_d_d_first = -inc.d_d_d_second * Exp(inc.d).transpose();
  return inc;
}

// One Gauss-Newton step on the control rotations; returns max |step|.
double RotationStep(const std::vector<Sample>& samples,
                    const CurveFitOptions& o,
                    std::vector<Eigen::Quaterniond>* rotations) {
  const int n = static_cast<int>(rotations->size());
  const double dt = o.knot_spacing_s;
  const PoseSpline spline(0.0, dt, std::vector<Eigen::Vector3d>(n), *rotations);
  Triplets h;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * n);
  using Matrix12d = Eigen::Matrix<double, 12, 12>;
  std::vector<Matrix12d> segment(n - 3, Matrix12d::Zero());
  // Data: r = Log(R_k^T R(t_k)) / sr, d r = Jr^-1(r) sum_j J_j e_j / sr.
  for (const Sample& s : samples) {
    std::array<Eigen::Matrix3d, PoseSpline::kOrder> d_R;
    int first = 0;
    const Eigen::Quaterniond q = spline.Rotation(s.t, &d_R, &first);
    const Eigen::Vector3d r = Log(s.q.conjugate() * q) / o.rotation_sigma_rad;
    const Eigen::Matrix3d jr_inv =
        RightJacobianInverse(r * o.rotation_sigma_rad) / o.rotation_sigma_rad;
    Eigen::Matrix<double, 3, 12> J;
    for (int k = 0; k < 4; ++k) J.middleCols<3>(3 * k) = jr_inv * d_R[k];
    segment[first] += J.transpose() * J;
    g.segment<12>(3 * first) += J.transpose() * r;
  }
  for (int i = 0; i + 3 < n; ++i) AddBlock(3 * i, 3 * i, segment[i], &h);
  // Smoothness: e = (d_{i+1} - d_i) / (sw dt^2) on R_i, R_{i+1}, R_{i+2}.
  const double scale = 1.0 / (o.angular_acceleration_sigma * dt * dt);
  for (int i = 0; i + 2 < n; ++i) {
    const Increment a = IncrementOf((*rotations)[i], (*rotations)[i + 1]);
    const Increment b = IncrementOf((*rotations)[i + 1], (*rotations)[i + 2]);
    const Eigen::Vector3d e = scale * (b.d - a.d);
    Eigen::Matrix<double, 3, 9> J;
    J.leftCols<3>() = -scale * a.d_d_d_first;
    J.middleCols<3>(3) = scale * (b.d_d_d_first - a.d_d_d_second);
    J.rightCols<3>() = scale * b.d_d_d_second;
    AddBlock(3 * i, 3 * i, J.transpose() * J, &h);
    g.segment<9>(3 * i) += J.transpose() * e;
  }
  const Eigen::VectorXd step = -Solve(Assemble(3 * n, h), g);
  for (int k = 0; k < n; ++k) {
    (*rotations)[k] =
        ((*rotations)[k] * ExpQuaternion(step.segment<3>(3 * k))).normalized();
  }
  return step.cwiseAbs().maxCoeff();
}

void Measure(const std::vector<Sample>& samples, const PoseSpline& spline,
             CurveFitReport* report) {
  double sum_p = 0.0, sum_r = 0.0;
  for (const Sample& s : samples) {
    const PoseSplineState x = spline.Evaluate(s.t);
    const double ep = (x.p - s.p).norm();
    const double er = Log(s.q.conjugate() * x.q).norm();
    sum_p += ep * ep;
    sum_r += er * er;
    report->position_max_m = std::max(report->position_max_m, ep);
    report->rotation_max_rad = std::max(report->rotation_max_rad, er);
  }
  report->position_rms_m = std::sqrt(sum_p / samples.size());
  report->rotation_rms_rad = std::sqrt(sum_r / samples.size());
}

PoseSpline Fit(const std::vector<StampedPose>& poses, const CurveFitOptions& o,
               CurveFitReport* report) {
  std::string message;
  if (!o.Validate(&message)) {
    throw std::invalid_argument("CurveFitOptions: " + message);
  }
  if (poses.size() < 2) {
    throw std::invalid_argument("TrajectoryCurve: needs at least 2 poses");
  }
  std::vector<Sample> samples;
  for (size_t k = 0; k < poses.size(); ++k) {
    if (k > 0 && poses[k].t_ns <= poses[k - 1].t_ns) {
      throw std::invalid_argument("TrajectoryCurve: stamps must increase (" +
                                  std::to_string(poses[k].t_ns) + " after " +
                                  std::to_string(poses[k - 1].t_ns) + ")");
    }
    samples.push_back(
        {static_cast<double>(poses[k].t_ns - poses.front().t_ns) * 1e-9,
         poses[k].p_w_b, poses[k].q_w_b.normalized()});
  }
  const double duration = samples.back().t;
  if (duration < o.knot_spacing_s) {
    throw std::invalid_argument(
        "TrajectoryCurve: the poses span less than one knot spacing");
  }
  const int n =
      static_cast<int>(std::ceil(duration / o.knot_spacing_s - 1e-9)) + 3;
  std::vector<Eigen::Quaterniond> rotations(n);
  for (int k = 0; k < n; ++k) {
    rotations[k] = Interpolate(samples, (k - 1) * o.knot_spacing_s);
  }
  report->samples = static_cast<int>(samples.size());
  report->control_points = n;
  while (report->iterations < o.max_iterations) {
    ++report->iterations;
    if (RotationStep(samples, o, &rotations) < 1e-10) break;
  }
  PoseSpline spline(0.0, o.knot_spacing_s, FitPositions(samples, n, o),
                    rotations);
  Measure(samples, spline, report);
  return spline;
}

}  // namespace

bool CurveFitOptions::Validate(std::string* message) const {
  const struct {
    const char* name;
    double value;
  } positive[] = {{"knot_spacing_s", knot_spacing_s},
                  {"position_sigma_m", position_sigma_m},
                  {"rotation_sigma_rad", rotation_sigma_rad},
                  {"acceleration_sigma", acceleration_sigma},
                  {"angular_acceleration_sigma", angular_acceleration_sigma}};
  for (const auto& f : positive) {
    if (!(std::isfinite(f.value) && f.value > 0.0)) {
      *message = std::string(f.name) + " must be > 0 (got " +
                 std::to_string(f.value) + ")";
      return false;
    }
  }
  if (!(std::isfinite(rotation_knot_spacing_s) &&
        rotation_knot_spacing_s >= 0.0)) {
    *message = "rotation_knot_spacing_s must be >= 0 (got " +
               std::to_string(rotation_knot_spacing_s) + ")";
    return false;
  }
  if (max_iterations < 1) {
    *message = "max_iterations must be >= 1";
    return false;
  }
  return true;
}

TrajectoryCurve::TrajectoryCurve(const std::vector<StampedPose>& poses,
                                 const CurveFitOptions& options)
    : start_ns_(poses.empty() ? 0 : poses.front().t_ns),
      end_ns_(poses.empty() ? 0 : poses.back().t_ns),
      spline_(Fit(poses, options, &report_)) {
  const double rotation_spacing = options.rotation_knot_spacing_s;
  if (rotation_spacing > 0.0 && rotation_spacing != options.knot_spacing_s) {
    CurveFitOptions rotation_options = options;
    rotation_options.knot_spacing_s = rotation_spacing;
    CurveFitReport rotation_report;
    rotation_spline_.emplace(Fit(poses, rotation_options, &rotation_report));
    report_.rotation_rms_rad = rotation_report.rotation_rms_rad;
    report_.rotation_max_rad = rotation_report.rotation_max_rad;
    report_.control_points += rotation_report.control_points;
    report_.iterations = rotation_report.iterations;
  }
}

TrajectoryCurve::TrajectoryCurve(int64_t start_ns, int64_t end_ns,
                                 PoseSpline spline,
                                 const CurveFitReport& report)
    : start_ns_(start_ns),
      end_ns_(end_ns),
      report_(report),
      spline_(std::move(spline)) {}

SimState TrajectoryCurve::At(double t) const {
  const PoseSplineState x = spline_.Evaluate(t);
  SimState s;
  s.p_w_b = x.p;
  s.v_w = x.v;
  s.a_w = x.a;
  s.q_w_b = x.q;
  s.w_b = x.w;
  if (rotation_spline_.has_value()) {
    const PoseSplineState r = rotation_spline_->Evaluate(t);
    s.q_w_b = r.q;
    s.w_b = r.w;
  }
  return s;
}

}  // namespace vio
