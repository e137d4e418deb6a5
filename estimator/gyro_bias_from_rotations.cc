#include "estimator/gyro_bias_from_rotations.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>
#include <utility>

namespace vio {
namespace {

// Unit bearings of the features frames i and j share.
struct PairBearings {
  int i = 0, j = 0;
  std::vector<Eigen::Vector3d> u_i, u_j;  // unit bearings in the cameras
};

std::vector<PairBearings> PairsOf(const std::vector<GyroAidedTrack>& tracks,
                                  int n) {
  constexpr int kPairStep = 4;
  std::vector<std::vector<std::pair<int, Eigen::Vector3d>>> by_frame(n);
  for (size_t t = 0; t < tracks.size(); ++t) {
    for (const GyroAidedSighting& s : tracks[t].sightings) {
      by_frame[s.frame].push_back(
          {static_cast<int>(t),
           Eigen::Vector3d(s.xy.x(), s.xy.y(), 1.0).normalized()});
    }
  }
  std::vector<PairBearings> pairs;
  for (int i = 0; i + kPairStep < n; ++i) {
    PairBearings p;
    p.i = i;
    p.j = i + kPairStep;
    std::map<int, Eigen::Vector3d> at_j(by_frame[p.j].begin(),
                                        by_frame[p.j].end());
    for (const auto& [t, u] : by_frame[i]) {
      const auto it = at_j.find(t);
      if (it == at_j.end()) continue;
      p.u_i.push_back(u);
      p.u_j.push_back(it->second);
    }
    if (p.u_i.size() >= 8) pairs.push_back(std::move(p));
  }
  return pairs;
}

double EpipolarCost(const GyroAidedAttitudes& attitudes,
                    const Eigen::Matrix3d& R_b_c,
                    const std::vector<PairBearings>& pairs,
                    const Eigen::Vector3d& b_g) {
  const std::vector<Eigen::Matrix3d> R_v_c =
      attitudes.CameraAttitudes(b_g, R_b_c);
  double cost = 0.0;
  for (const PairBearings& p : pairs) {
    const Eigen::Matrix3d R_ci_cj = R_v_c[p.i].transpose() * R_v_c[p.j];
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    for (size_t f = 0; f < p.u_i.size(); ++f) {
      const Eigen::Vector3d n = p.u_i[f].cross(R_ci_cj * p.u_j[f]);
      M += n * n.transpose();
    }
    cost += Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(
                M, Eigen::EigenvaluesOnly)
                .eigenvalues()(0);
  }
  return cost;
}

}  // namespace

bool FitGyroBiasFromRotations(const GyroAidedProblem& problem,
                              Eigen::Vector3d* b_g) {
  return FitGyroBiasFromRotations(GyroAidedAttitudes::Of(problem.from_first),
                                  problem.tracks, problem.T_b_c.linear(), b_g);
}

bool FitGyroBiasFromRotations(const GyroAidedAttitudes& attitudes,
                              const std::vector<GyroAidedTrack>& tracks,
                              const Eigen::Matrix3d& R_b_c,
                              Eigen::Vector3d* b_g) {
  constexpr int kIterations = 8;
  constexpr double kStep = 2e-4;     // [rad/s]
  constexpr double kMaxStep = 0.05;  // per iteration [rad/s]
  const std::vector<PairBearings> pairs =
      PairsOf(tracks, attitudes.NumFrames());
  if (pairs.size() < 3) return false;
  auto f = [&](const Eigen::Vector3d& b) {
    return EpipolarCost(attitudes, R_b_c, pairs, b);
  };
  double cost = f(*b_g);
  for (int it = 0; it < kIterations; ++it) {
    Eigen::Vector3d grad;
    Eigen::Matrix3d hess;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d ea = kStep * Eigen::Vector3d::Unit(a);
      const double fp = f(*b_g + ea), fm = f(*b_g - ea);
      grad(a) = (fp - fm) / (2 * kStep);
      hess(a, a) = (fp - 2 * cost + fm) / (kStep * kStep);
      for (int c = a + 1; c < 3; ++c) {
        const Eigen::Vector3d ec = kStep * Eigen::Vector3d::Unit(c);
        hess(a, c) = hess(c, a) = (f(*b_g + ea + ec) - f(*b_g + ea - ec) -
                                   f(*b_g - ea + ec) + f(*b_g - ea - ec)) /
                                  (4 * kStep * kStep);
      }
    }
    Eigen::Vector3d step = -hess.ldlt().solve(grad);
    // Not a descent direction (the Hessian not positive): a gradient step.
    if (!step.allFinite() || step.dot(grad) >= 0.0) {
      step = -grad * (kMaxStep / std::max(grad.norm(), 1e-300));
    }
    if (step.norm() > kMaxStep) step *= kMaxStep / step.norm();
    bool improved = false;
    for (int tries = 0; tries < 6 && !improved; ++tries, step *= 0.5) {
      const double next = f(*b_g + step);
      if (next < cost) {
        *b_g += step;
        cost = next;
        improved = true;
      }
    }
    if (!improved || step.norm() < 1e-6) break;
  }
  return b_g->allFinite();
}

}  // namespace vio
