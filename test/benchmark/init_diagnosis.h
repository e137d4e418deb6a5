#ifndef VIO_TEST_BENCHMARK_INIT_DIAGNOSIS_H_
#define VIO_TEST_BENCHMARK_INIT_DIAGNOSIS_H_

// init_benchmark --diagnose: why the monocular start in motion is refused,
// measured on the simulation against its truth (docs/initialisation.md,
// "Why the hand-held start is late"). Per trial, at every frame until the
// start:
//   - the pairs (k, newest) of the frames the start selects: features
//     shared, their parallax after the Kabsch rotation the start takes out
//     (what min_parallax_px is compared with), after the TRUE rotation (what
//     the translation alone makes), and the true translation and depths;
//   - the structure from motion's own verdict on those frames;
// and how long the camera-0 tracks live. Header-only: the benchmark's only
// translation unit includes it.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "dataset/simulator.h"
#include "estimator/estimator.h"
#include "estimator/in_motion_start.h"
#include "estimator/structure_from_motion.h"

namespace vio {
namespace diagnosis {

inline double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

inline double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t k = static_cast<size_t>(q * (v.size() - 1) + 0.5);
  return v[std::min(k, v.size() - 1)];
}

// The truth's camera-0 pose at an IMU stamp (the nearest later state).
inline Eigen::Isometry3d TrueCamera(const Simulation& sim, int64_t t_ns,
                                    const Eigen::Isometry3d& T_b_c) {
  const auto it = std::lower_bound(
      sim.ground_truth.begin(), sim.ground_truth.end(), t_ns,
      [](const StampedState& s, int64_t t) { return s.t_ns < t; });
  const StampedState& s =
      it == sim.ground_truth.end() ? sim.ground_truth.back() : *it;
  Eigen::Isometry3d T_w_b = Eigen::Isometry3d::Identity();
  T_w_b.linear() = s.q_w_b.toRotationMatrix();
  T_w_b.translation() = s.p_w_b;
  return T_w_b * T_b_c;
}

// The median distance [normalised] between x_b and the bearings x_a rotated
// by R_b_a (no Kabsch fit).
inline double ParallaxAfterRotation(const std::vector<Eigen::Vector2d>& x_a,
                                    const std::vector<Eigen::Vector2d>& x_b,
                                    const Eigen::Matrix3d& R_b_a) {
  std::vector<double> d;
  for (size_t i = 0; i < x_a.size(); ++i) {
    const Eigen::Vector3d f = R_b_a * x_a[i].homogeneous();
    if (f.z() > 0.0) d.push_back((f.hnormalized() - x_b[i]).norm());
  }
  return Median(d);
}

struct PairFigures {
  double age_s = 0.0;        // newest minus frame k [s]
  int shared = 0;            // camera-0 features in both
  double kabsch_px = 0.0;    // rotation-compensated as the start measures it
  double true_rot_px = 0.0;  // after the true rotation
  double baseline_m = 0.0;   // true |t| between the cameras
  double depth_m = 0.0;      // median true depth of the shared in newest
  // The pair's own relative pose (essential matrix, no parallax threshold)
  // against the truth: angle of the translation direction [deg], <0: none.
  double direction_error_deg = -1.0;
};

// Pairs (each selected frame, newest) of `frames` for the start's selection.
inline std::vector<PairFigures> Pairs(const Simulation& sim,
                                      const std::vector<BufferedFrame>& frames,
                                      const std::vector<int>& selected,
                                      const Eigen::Isometry3d& T_b_c,
                                      double focal_px) {
  std::vector<PairFigures> out;
  const BufferedFrame& n = frames[selected.back()];
  std::map<int64_t, Eigen::Vector2d> xn;
  for (const FeatureObservation& o : n.observations) {
    if (o.camera == 0) xn[o.feature_id] = o.xy;
  }
  const Eigen::Isometry3d T_w_cn = TrueCamera(sim, n.t_imu_ns, T_b_c);
  for (size_t s = 0; s + 1 < selected.size(); ++s) {
    const BufferedFrame& a = frames[selected[s]];
    std::vector<Eigen::Vector2d> xa_v, xn_v;
    std::vector<double> depth;
    for (const FeatureObservation& o : a.observations) {
      if (o.camera != 0) continue;
      const auto it = xn.find(o.feature_id);
      if (it == xn.end()) continue;
      xa_v.push_back(o.xy);
      xn_v.push_back(it->second);
      const int lm = sim.landmark_of_feature[o.feature_id];
      depth.push_back((T_w_cn.inverse() * sim.landmarks_w[lm]).z());
    }
    const Eigen::Isometry3d T_w_ca = TrueCamera(sim, a.t_imu_ns, T_b_c);
    const Eigen::Isometry3d T_n_a = T_w_cn.inverse() * T_w_ca;
    PairFigures p;
    p.age_s = 1e-9 * static_cast<double>(n.t_ns - a.t_ns);
    p.shared = static_cast<int>(xa_v.size());
    p.kabsch_px = focal_px * RotationCompensatedParallax(xa_v, xn_v);
    p.true_rot_px =
        focal_px * ParallaxAfterRotation(xa_v, xn_v, T_n_a.linear());
    p.baseline_m = T_n_a.translation().norm();
    p.depth_m = Median(depth);
    SfmFrame fa, fn;
    for (size_t i = 0; i < xa_v.size(); ++i) {
      fa.xy[static_cast<int64_t>(i)] = xa_v[i];
      fn.xy[static_cast<int64_t>(i)] = xn_v[i];
    }
    SfmOptions o;
    o.focal_px = focal_px;
    o.min_parallax_px = 0.0;
    o.min_correspondences = 8;
    o.min_inliers = 8;
    o.ransac_threshold_px = 2.0;
    const SfmResult r = SolveStructureFromMotion({fa, fn}, o);
    if (r.failure == InitFailure::kNone) {
      const Eigen::Vector3d t_est = r.T_v_c[1].translation().normalized();
      const Eigen::Vector3d t_true =
          (T_n_a.inverse().translation()).normalized();
      p.direction_error_deg =
          std::atan2(t_est.cross(t_true).norm(), t_est.dot(t_true)) * 180.0 /
          M_PI;
    }
    out.push_back(p);
  }
  return out;
}

// Over every pair (i < j) of the selected frames sharing at least
// min_shared features: the largest rotation-compensated parallax [px], and
// in *ages the two frames' ages [s] (newest = 0).
inline double BestAnyPair(const std::vector<BufferedFrame>& frames,
                          const std::vector<int>& selected, int min_shared,
                          double focal_px, std::pair<double, double>* ages) {
  double best = 0.0;
  const int64_t t_n = frames[selected.back()].t_ns;
  for (size_t i = 0; i < selected.size(); ++i) {
    std::map<int64_t, Eigen::Vector2d> xi;
    for (const FeatureObservation& o : frames[selected[i]].observations) {
      if (o.camera == 0) xi[o.feature_id] = o.xy;
    }
    for (size_t j = i + 1; j < selected.size(); ++j) {
      std::vector<Eigen::Vector2d> a, b;
      for (const FeatureObservation& o : frames[selected[j]].observations) {
        const auto it = xi.find(o.feature_id);
        if (o.camera != 0 || it == xi.end()) continue;
        a.push_back(it->second);
        b.push_back(o.xy);
      }
      if (static_cast<int>(a.size()) < min_shared) continue;
      const double px = focal_px * RotationCompensatedParallax(a, b);
      if (px > best) {
        best = px;
        *ages = {1e-9 * static_cast<double>(t_n - frames[selected[i]].t_ns),
                 1e-9 * static_cast<double>(t_n - frames[selected[j]].t_ns)};
      }
    }
  }
  return best;
}

// Of the camera-0 features of every frame in [t0, t1), the share still
// tracked dt later, for each dt of `lags` [s].
inline std::vector<double> Survival(const std::vector<FeatureFrame>& frames,
                                    const std::vector<double>& lags) {
  std::map<int64_t, int64_t> last_seen;
  for (const FeatureFrame& f : frames) {
    for (const FeatureObservation& o : f.observations) {
      if (o.camera == 0) last_seen[o.feature_id] = f.t_ns;
    }
  }
  std::vector<double> share;
  const int64_t t_end = frames.back().t_ns;
  for (double lag : lags) {
    const int64_t lag_ns = std::llround(lag * 1e9);
    int64_t alive = 0, total = 0;
    for (const FeatureFrame& f : frames) {
      if (f.t_ns + lag_ns > t_end) break;
      for (const FeatureObservation& o : f.observations) {
        if (o.camera != 0) continue;
        ++total;
        alive += last_seen[o.feature_id] >= f.t_ns + lag_ns ? 1 : 0;
      }
    }
    share.push_back(total > 0 ? static_cast<double>(alive) / total : NAN);
  }
  return share;
}

}  // namespace diagnosis
}  // namespace vio

#endif  // VIO_TEST_BENCHMARK_INIT_DIAGNOSIS_H_
