#include "dataset/imu_curve_fit.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "geometry/so3.h"

namespace vio {
namespace {

struct Pose {
  double t;  // seconds after the first pose
  Eigen::Vector3d p;
  Eigen::Quaterniond q;
};

struct Sample {
  double t;  // seconds after the first pose
  Eigen::Vector3d gyr, acc;
};

// J^T J and J^T r of the whitened terms, in 3x3 blocks (upper triangle).
class NormalEquations {
 public:
  explicit NormalEquations(int blocks)
      : blocks_(blocks), g_(Eigen::VectorXd::Zero(3 * blocks)) {
    h_.reserve(static_cast<size_t>(blocks) * 12);
  }
  void Add(const CurveTerm& term, double sigma) {
    const Eigen::VectorXd r = term.r / sigma;
    const Eigen::MatrixXd J = term.J / sigma;
    const int k = static_cast<int>(term.blocks.size());
    for (int a = 0; a < k; ++a) {
      const int row = term.blocks[a];
      g_.segment<3>(3 * row) += J.middleCols<3>(3 * a).transpose() * r;
      for (int b = 0; b < k; ++b) {
        const int col = term.blocks[b];
        if (col < row) continue;
        const Eigen::Matrix3d jtj =
            J.middleCols<3>(3 * a).transpose() * J.middleCols<3>(3 * b);
        auto it = h_.try_emplace(Key(row, col), Eigen::Matrix3d::Zero()).first;
        it->second += jtj;
      }
    }
  }
  // The Gauss-Newton step -H^-1 g.
  Eigen::VectorXd Step() const {
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(h_.size() * 18);
    for (const auto& [key, m] : h_) {
      const int row = static_cast<int>(key / blocks_);
      const int col = static_cast<int>(key % blocks_);
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
          triplets.emplace_back(3 * row + r, 3 * col + c, m(r, c));
          if (row != col)
            triplets.emplace_back(3 * col + c, 3 * row + r, m(r, c));
        }
      }
    }
    Eigen::SparseMatrix<double> h(3 * blocks_, 3 * blocks_);
    h.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(h);
    if (ldlt.info() != Eigen::Success) {
      throw std::invalid_argument(
          "FitCurveToImu: the fit's normal equations are singular");
    }
    return -ldlt.solve(g_);
  }

 private:
  int64_t Key(int row, int col) const {
    return static_cast<int64_t>(row) * blocks_ + col;
  }
  int blocks_;
  std::unordered_map<int64_t, Eigen::Matrix3d> h_;
  Eigen::VectorXd g_;
};

// Everything the fit weighs, with its noise.
struct Problem {
  std::vector<Pose> poses;
  std::vector<Sample> imu;
  double mean_interval_s = 0.0;
  double gyro_density = 0.0, acc_density = 0.0;  // scaled [SI/sqrt(Hz)]
  double gyro_walk = 0.0, acc_walk = 0.0;        // scaled [SI/sqrt(Hz)]
};

void AddTerms(const Problem& p, const ImuCurveFitOptions& o,
              const ImuCurveState& state, NormalEquations* ne) {
  const PoseSpline spline = state.Spline();
  for (const Pose& pose : p.poses) {
    ne->Add(PositionTerm(state, spline, pose.t, pose.p), o.position_sigma_m);
    ne->Add(RotationTerm(state, spline, pose.t, pose.q), o.rotation_sigma_rad);
  }
  const double acc_sigma = p.acc_density / std::sqrt(p.mean_interval_s);
  for (size_t k = 0; k < p.imu.size(); ++k) {
    const Sample& s = p.imu[k];
    ne->Add(AccelerometerTerm(state, spline, s.t, s.acc, o.gravity_m_s2),
            acc_sigma);
    if (k + 1 == p.imu.size()) continue;
    const Sample& next = p.imu[k + 1];
    const double dt = next.t - s.t;
    ne->Add(
        GyroIntervalTerm(state, spline, s.t, next.t, 0.5 * (s.gyr + next.gyr)),
        p.gyro_density * std::sqrt(dt));
  }
  const double dt2 = state.knot_spacing_s * state.knot_spacing_s;
  for (int i = 1; i + 1 < state.control_points(); ++i) {
    ne->Add(PositionSmoothnessTerm(state, i), o.acceleration_sigma * dt2);
    ne->Add(RotationSmoothnessTerm(state, i),
            o.angular_acceleration_sigma * dt2);
  }
  const double root_t = std::sqrt(state.bias_knot_spacing_s);
  for (int m = 0; m + 1 < state.bias_knots(); ++m) {
    ne->Add(BiasWalkTerm(state, m, true), p.gyro_walk * root_t);
    ne->Add(BiasWalkTerm(state, m, false), p.acc_walk * root_t);
  }
}

// The pose at t interpolated from the ground truth (held at the ends).
Pose Interpolate(const std::vector<Pose>& poses, double t) {
  if (t <= poses.front().t) return {t, poses.front().p, poses.front().q};
  if (t >= poses.back().t) return {t, poses.back().p, poses.back().q};
  const auto after =
      std::upper_bound(poses.begin(), poses.end(), t,
                       [](double x, const Pose& s) { return x < s.t; });
  const Pose& a = *(after - 1);
  const double u = (t - a.t) / (after->t - a.t);
  return {t, (1.0 - u) * a.p + u * after->p, a.q.slerp(u, after->q)};
}

ImuCurveState InitialState(const Problem& p, const ImuCurveFitOptions& o) {
  const double duration = p.poses.back().t;
  ImuCurveState state;
  state.knot_spacing_s = o.knot_spacing_s;
  state.bias_knot_spacing_s = o.bias_knot_spacing_s;
  const int n =
      static_cast<int>(std::ceil(duration / o.knot_spacing_s - 1e-9)) + 3;
  // Control point k lies near the curve at (k - 1) dt.
  for (int k = 0; k < n; ++k) {
    const Pose x = Interpolate(p.poses, (k - 1) * o.knot_spacing_s);
    state.positions.push_back(x.p);
    state.rotations.push_back(x.q);
  }
  const int m =
      static_cast<int>(std::ceil(duration / o.bias_knot_spacing_s - 1e-9)) + 1;
  state.b_g.assign(std::max(m, 2), Eigen::Vector3d::Zero());
  state.b_a.assign(std::max(m, 2), Eigen::Vector3d::Zero());
  return state;
}

void Measure(const Problem& p, const ImuCurveFitOptions& o,
             const ImuCurveState& state, ImuCurveFitReport* report) {
  const PoseSpline spline = state.Spline();
  double sum_p = 0.0, sum_r = 0.0;
  for (const Pose& pose : p.poses) {
    const double ep = PositionTerm(state, spline, pose.t, pose.p).r.norm();
    const double er = RotationTerm(state, spline, pose.t, pose.q).r.norm();
    sum_p += ep * ep;
    sum_r += er * er;
    report->position_max_m = std::max(report->position_max_m, ep);
    report->rotation_max_rad = std::max(report->rotation_max_rad, er);
  }
  report->position_rms_m = std::sqrt(sum_p / p.poses.size());
  report->rotation_rms_rad = std::sqrt(sum_r / p.poses.size());
  Eigen::Vector3d sum_g = Eigen::Vector3d::Zero(), sum_a = sum_g;
  for (size_t k = 0; k < p.imu.size(); ++k) {
    const Sample& s = p.imu[k];
    sum_a += AccelerometerTerm(state, spline, s.t, s.acc, o.gravity_m_s2)
                 .r.cwiseAbs2();
    if (k + 1 == p.imu.size()) continue;
    const Sample& next = p.imu[k + 1];
    const Eigen::Vector3d r =
        GyroIntervalTerm(state, spline, s.t, next.t, 0.5 * (s.gyr + next.gyr))
            .r /
        (next.t - s.t);
    sum_g += r.cwiseAbs2();
  }
  const double n = static_cast<double>(p.imu.size());
  report->accelerometer_rms = (sum_a / n).cwiseSqrt();
  report->gyroscope_rms = (sum_g / (n - 1.0)).cwiseSqrt();
}

Problem MakeProblem(const std::vector<StampedPose>& poses,
                    const std::vector<ImuSample>& imu, const ImuNoise& noise,
                    const ImuCurveFitOptions& o) {
  std::string message;
  if (!o.Validate(&message)) {
    throw std::invalid_argument("ImuCurveFitOptions: " + message);
  }
  if (!noise.Validate(&message)) {
    throw std::invalid_argument("FitCurveToImu: imu noise: " + message);
  }
  Problem p;
  for (size_t k = 0; k < poses.size(); ++k) {
    if (k > 0 && poses[k].t_ns <= poses[k - 1].t_ns) {
      throw std::invalid_argument("FitCurveToImu: pose stamps must increase (" +
                                  std::to_string(poses[k].t_ns) + " after " +
                                  std::to_string(poses[k - 1].t_ns) + ")");
    }
    p.poses.push_back(
        {static_cast<double>(poses[k].t_ns - poses[0].t_ns) * 1e-9,
         poses[k].p_w_b, poses[k].q_w_b.normalized()});
  }
  if (p.poses.size() < 2 || p.poses.back().t < 4.0 * o.knot_spacing_s) {
    throw std::invalid_argument(
        "FitCurveToImu: the poses span less than 4 knot spacings");
  }
  const int64_t start = poses.front().t_ns, end = poses.back().t_ns;
  for (size_t k = 0; k < imu.size(); ++k) {
    if (k > 0 && imu[k].t_ns <= imu[k - 1].t_ns) {
      throw std::invalid_argument("FitCurveToImu: IMU stamps must increase (" +
                                  std::to_string(imu[k].t_ns) + " after " +
                                  std::to_string(imu[k - 1].t_ns) + ")");
    }
    if (imu[k].t_ns < start || imu[k].t_ns > end) continue;
    p.imu.push_back({static_cast<double>(imu[k].t_ns - start) * 1e-9,
                     imu[k].gyr, imu[k].acc});
  }
  if (p.imu.size() < 100) {
    throw std::invalid_argument(
        "FitCurveToImu: fewer than 100 IMU samples inside the poses' span");
  }
  p.mean_interval_s = (p.imu.back().t - p.imu.front().t) / (p.imu.size() - 1);
  p.gyro_density = noise.gyroscope_noise_density * o.gyroscope_noise_scale;
  p.acc_density =
      noise.accelerometer_noise_density * o.accelerometer_noise_scale;
  p.gyro_walk = noise.gyroscope_random_walk * o.bias_walk_scale;
  p.acc_walk = noise.accelerometer_random_walk * o.bias_walk_scale;
  return p;
}

}  // namespace

bool ImuCurveFitOptions::Validate(std::string* message) const {
  const struct {
    const char* name;
    double value;
  } positive[] = {{"knot_spacing_s", knot_spacing_s},
                  {"bias_knot_spacing_s", bias_knot_spacing_s},
                  {"gravity_m_s2", gravity_m_s2},
                  {"position_sigma_m", position_sigma_m},
                  {"rotation_sigma_rad", rotation_sigma_rad},
                  {"gyroscope_noise_scale", gyroscope_noise_scale},
                  {"accelerometer_noise_scale", accelerometer_noise_scale},
                  {"bias_walk_scale", bias_walk_scale},
                  {"acceleration_sigma", acceleration_sigma},
                  {"angular_acceleration_sigma", angular_acceleration_sigma}};
  for (const auto& f : positive) {
    if (!(std::isfinite(f.value) && f.value > 0.0)) {
      *message = std::string(f.name) + " must be > 0 (got " +
                 std::to_string(f.value) + ")";
      return false;
    }
  }
  if (max_iterations < 1) {
    *message = "max_iterations must be >= 1";
    return false;
  }
  return true;
}

Eigen::Vector3d ImuCurveFit::GyroBiasAt(int64_t t_ns) const {
  return state.GyroBias(static_cast<double>(t_ns - curve.start_ns()) * 1e-9);
}

Eigen::Vector3d ImuCurveFit::AccelBiasAt(int64_t t_ns) const {
  return state.AccelBias(static_cast<double>(t_ns - curve.start_ns()) * 1e-9);
}

ImuCurveFit FitCurveToImu(const std::vector<StampedPose>& poses,
                          const std::vector<ImuSample>& imu,
                          const ImuNoise& noise,
                          const ImuCurveFitOptions& options) {
  const Problem problem = MakeProblem(poses, imu, noise, options);
  ImuCurveState state = InitialState(problem, options);
  ImuCurveFitReport report;
  report.poses = static_cast<int>(problem.poses.size());
  report.imu_samples = static_cast<int>(problem.imu.size());
  report.control_points = state.control_points();
  report.bias_knots = state.bias_knots();
  while (report.iterations < options.max_iterations) {
    ++report.iterations;
    NormalEquations ne(state.blocks());
    AddTerms(problem, options, state, &ne);
    const Eigen::VectorXd step = ne.Step();
    for (int b = 0; b < state.blocks(); ++b) {
      state.Plus(b, step.segment<3>(3 * b));
    }
    // Converged when no control point moves by more than 1 um or 1 urad.
    if (step.cwiseAbs().maxCoeff() < 1e-6) break;
  }
  Measure(problem, options, state, &report);
  CurveFitReport curve_report;
  curve_report.samples = report.poses;
  curve_report.control_points = report.control_points;
  curve_report.iterations = report.iterations;
  curve_report.position_rms_m = report.position_rms_m;
  curve_report.position_max_m = report.position_max_m;
  curve_report.rotation_rms_rad = report.rotation_rms_rad;
  curve_report.rotation_max_rad = report.rotation_max_rad;
  return {TrajectoryCurve(poses.front().t_ns, poses.back().t_ns, state.Spline(),
                          curve_report),
          state, report};
}

}  // namespace vio
