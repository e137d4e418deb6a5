#include "estimator/structure_from_motion.h"

#include <ceres/ceres.h>

#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <set>

#include "estimator/sighting_outliers.h"
#include "estimator/triangulation.h"
#include "estimator/window.h"
#include "factors/pose_manifold.h"
#include "factors/reprojection_factor.h"

namespace vio {
namespace {

// How far a candidate reference pair got; a later stage is a better excuse.
enum Stage { kCorrespondences = 0, kParallax = 1, kInliers = 2, kDone = 3 };

struct Candidate {
  Stage stage = kCorrespondences;
  InitFailure failure = InitFailure::kFewCorrespondences;
  double value = 0.0, limit = 0.0;
  double parallax_px = 0.0;
  int inliers = 0;
  Eigen::Isometry3d T_l_n = Eigen::Isometry3d::Identity();  // camera n in l
  std::vector<int64_t> inlier_ids;
};

std::vector<int64_t> CommonIds(const SfmFrame& a, const SfmFrame& b) {
  std::vector<int64_t> ids;
  for (const auto& [id, xy] : a.xy) {
    if (b.xy.count(id) > 0) ids.push_back(id);
  }
  return ids;
}

cv::Mat Identity3() { return cv::Mat::eye(3, 3, CV_64F); }

// The relative pose of the newest frame n against frame l from the essential
// matrix: x_n ~ R x_l + t, so T_l_n = [R | t]^-1.
Candidate TryPair(const SfmFrame& l, const SfmFrame& n,
                  const SfmOptions& options) {
  Candidate c;
  const std::vector<int64_t> ids = CommonIds(l, n);
  c.value = static_cast<double>(ids.size());
  c.limit = options.min_correspondences;
  if (static_cast<int>(ids.size()) < options.min_correspondences) return c;
  std::vector<Eigen::Vector2d> xl, xn;
  std::vector<cv::Point2d> pl, pn;
  for (int64_t id : ids) {
    xl.push_back(l.xy.at(id));
    xn.push_back(n.xy.at(id));
    pl.emplace_back(xl.back().x(), xl.back().y());
    pn.emplace_back(xn.back().x(), xn.back().y());
  }
  c.stage = kParallax;
  c.failure = InitFailure::kLowParallax;
  c.parallax_px = options.focal_px * RotationCompensatedParallax(xl, xn);
  c.value = c.parallax_px;
  c.limit = options.min_parallax_px;
  if (c.parallax_px < options.min_parallax_px) return c;
  c.stage = kInliers;
  c.failure = InitFailure::kFewInliers;
  c.limit = options.min_inliers;
  cv::Mat mask;
  const cv::Mat E = cv::findEssentialMat(
      pl, pn, Identity3(), cv::RANSAC, 0.999,
      options.ransac_threshold_px / options.focal_px, mask);
  if (E.rows != 3 || E.cols != 3) return c;
  cv::Mat R, t;
  c.inliers = cv::recoverPose(E, pl, pn, Identity3(), R, t, mask);
  c.value = c.inliers;
  if (c.inliers < options.min_inliers) return c;
  Eigen::Isometry3d T_n_l = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) T_n_l.linear()(r, k) = R.at<double>(r, k);
    T_n_l.translation()[r] = t.at<double>(r);
  }
  c.T_l_n = T_n_l.inverse();
  for (size_t i = 0; i < ids.size(); ++i) {
    if (mask.at<uchar>(static_cast<int>(i)) != 0)
      c.inlier_ids.push_back(ids[i]);
  }
  c.stage = kDone;
  c.failure = InitFailure::kNone;
  return c;
}

// Triangulates every feature not yet in *points that at least two posed
// frames see; `only` (when non-empty) limits it to those ids.
void TriangulateMore(const std::vector<SfmFrame>& frames,
                     const std::vector<bool>& posed,
                     const std::vector<Eigen::Isometry3d>& T_v_c,
                     const SfmOptions& options, const std::set<int64_t>& only,
                     std::map<int64_t, Eigen::Vector3d>* points) {
  TriangulationOptions t;
  t.min_parallax_deg = options.min_ray_angle_deg;
  t.min_depth_m = 1e-3;  // arbitrary units: only "in front" matters
  t.max_depth_m = 1e4;
  t.min_observations = 2;
  std::map<int64_t, std::vector<TriangulationView>> views;
  for (size_t k = 0; k < frames.size(); ++k) {
    if (!posed[k]) continue;
    for (const auto& [id, xy] : frames[k].xy) {
      if (points->count(id) > 0 || (!only.empty() && only.count(id) == 0)) {
        continue;
      }
      views[id].push_back({T_v_c[k], xy});
    }
  }
  for (const auto& [id, v] : views) {
    Eigen::Vector3d p;
    double depth = 0.0;
    if (v.size() >= 2 &&
        Triangulate(v, t, &p, &depth) == TriangulationStatus::kOk) {
      (*points)[id] = p;
    }
  }
}

// One adjusted sighting's reprojection error after the adjustment (NaN
// where it could not be evaluated); a point's sightings are consecutive.
struct SightingError {
  int64_t id = -1;
  int frame = -1;
  double px = 0.0;
};

// Bundle adjustment over every pose and point (frame `fixed` held); returns
// the RMS reprojection error [px] after it, over all observations, and each
// one's error in *errors (the anchor sightings, which the others are
// measured against, have none).
double BundleAdjust(const std::vector<SfmFrame>& frames, int fixed,
                    const SfmOptions& options,
                    std::vector<Eigen::Isometry3d>* T_v_c,
                    std::map<int64_t, Eigen::Vector3d>* points,
                    std::vector<SightingError>* errors) {
  const int n = static_cast<int>(frames.size());
  std::vector<std::array<double, 7>> poses(n);
  for (int k = 0; k < n; ++k) poses[k] = PoseArray((*T_v_c)[k]);
  std::array<double, 7> identity = {0, 0, 0, 0, 0, 0, 1};
  // Each point as an inverse depth in the first frame that sees it.
  struct Point {
    int anchor = -1;
    double rho = 0.0;
  };
  std::map<int64_t, Point> rho;
  for (const auto& [id, p] : *points) {
    for (int k = 0; k < n; ++k) {
      if (frames[k].xy.count(id) == 0) continue;
      const double z = ((*T_v_c)[k].inverse() * p).z();
      if (z > 0.0) rho[id] = {k, 1.0 / z};
      break;
    }
  }
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::HuberLoss loss(2.0 * options.ransac_threshold_px);
  PoseManifold manifold;
  for (int k = 0; k < n; ++k) {
    problem.AddParameterBlock(poses[k].data(), 7, &manifold);
  }
  problem.SetParameterBlockConstant(poses[fixed].data());
  problem.AddParameterBlock(identity.data(), 7, &manifold);
  problem.SetParameterBlockConstant(identity.data());
  // Residuals in pixels; Huber beyond twice the RANSAC threshold.
  struct Term {
    std::unique_ptr<ceres::CostFunction> cost;
    std::vector<double*> blocks;
    int64_t id = -1;
    int frame = -1;
  };
  std::vector<Term> terms;
  for (auto& [id, point] : rho) {
    const Eigen::Vector2d& xa = frames[point.anchor].xy.at(id);
    for (int k = point.anchor + 1; k < n; ++k) {
      const auto it = frames[k].xy.find(id);
      if (it == frames[k].xy.end()) continue;
      Term t;
      t.cost = std::make_unique<ReprojectionFactor>(xa, it->second,
                                                    options.focal_px);
      t.blocks = {poses[point.anchor].data(), poses[k].data(), identity.data(),
                  &point.rho};
      t.id = id;
      t.frame = k;
      problem.AddResidualBlock(t.cost.get(), &loss, t.blocks);
      terms.push_back(std::move(t));
    }
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_SCHUR;
  so.max_num_iterations = options.bundle_iterations;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  // Per axis, so that 1 px of feature noise reads about 1 px.
  double sum = 0.0;
  int count = 0;
  errors->clear();
  for (const Term& t : terms) {
    Eigen::Vector2d r;
    double px = std::numeric_limits<double>::quiet_NaN();
    if (t.cost->Evaluate(t.blocks.data(), r.data(), nullptr)) {
      sum += r.squaredNorm();
      count += 2;
      px = r.norm();
    }
    errors->push_back({t.id, t.frame, px});
  }
  for (int k = 0; k < n; ++k) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(poses[k].data());
    T.linear() = Eigen::Quaterniond(poses[k].data() + 3).normalized().matrix();
    (*T_v_c)[k] = T;
  }
  points->clear();
  for (const auto& [id, point] : rho) {
    if (!(point.rho > 0.0)) continue;
    (*points)[id] = (*T_v_c)[point.anchor] *
                    (frames[point.anchor].xy.at(id).homogeneous() / point.rho);
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

}  // namespace

double RotationCompensatedParallax(const std::vector<Eigen::Vector2d>& x_a,
                                   const std::vector<Eigen::Vector2d>& x_b) {
  if (x_a.empty() || x_a.size() != x_b.size()) return 0.0;
  // Kabsch: R_b_a = argmin sum |f_b - R f_a|^2 over unit bearings, from the
  // SVD of H = sum f_a f_b^T = U S V^T: R = V diag(1, 1, det(V U^T)) U^T.
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < x_a.size(); ++i) {
    H += x_a[i].homogeneous().normalized() *
         x_b[i].homogeneous().normalized().transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(
      H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) =
      (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;
  const Eigen::Matrix3d R = svd.matrixV() * D * svd.matrixU().transpose();
  std::vector<double> d;
  for (size_t i = 0; i < x_a.size(); ++i) {
    const Eigen::Vector3d f = R * x_a[i].homogeneous();
    if (f.z() <= 0.0) continue;
    d.push_back((f.hnormalized() - x_b[i]).norm());
  }
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

SfmResult SolveStructureFromMotion(const std::vector<SfmFrame>& frames,
                                   const SfmOptions& options) {
  SfmResult result;
  const int n = static_cast<int>(frames.size());
  if (n < 2) {
    result.failure = InitFailure::kTooFewFrames;
    result.value = n;
    result.limit = 2;
    return result;
  }
  // 1. The oldest frame that pairs well with the newest; else the candidate
  // that got furthest explains the failure.
  Candidate best;
  int l = -1;
  for (int k = 0; k + 1 < n; ++k) {
    Candidate c = TryPair(frames[k], frames[n - 1], options);
    if (c.stage == kDone) {
      best = std::move(c);
      l = k;
      break;
    }
    if (c.stage > best.stage ||
        (c.stage == best.stage && c.value > best.value)) {
      best = std::move(c);
    }
  }
  result.parallax_px = best.parallax_px;
  result.inliers = best.inliers;
  if (l < 0) {
    result.failure = best.failure;
    result.value = best.value;
    result.limit = best.limit;
    return result;
  }
  result.reference = l;
  // 2. The pair's inliers.
  std::vector<Eigen::Isometry3d> T_v_c(n, Eigen::Isometry3d::Identity());
  std::vector<bool> posed(n, false);
  posed[l] = posed[n - 1] = true;
  T_v_c[n - 1] = best.T_l_n;
  std::map<int64_t, Eigen::Vector3d> points;
  const std::set<int64_t> inliers(best.inlier_ids.begin(),
                                  best.inlier_ids.end());
  TriangulateMore(frames, posed, T_v_c, options, inliers, &points);
  // 3. The other frames by PnP, nearest to a posed frame first.
  std::vector<int> order;
  for (int k = n - 2; k > l; --k) order.push_back(k);
  for (int k = l - 1; k >= 0; --k) order.push_back(k);
  for (int k : order) {
    // Frame k + 1 is placed already, whichever side of l k lies on.
    int pnp_inliers = 0;
    // With the neighbour's pose as OpenCV's guess, as the mono start's
    // figures and tests were measured; where the pose it returns does not
    // agree with its inliers (outlier sightings), without the guess
    // (PlaceCameraByPnp).
    if (!PlaceCameraByPnp(frames[k], points, &T_v_c[k + 1], options, &T_v_c[k],
                          &pnp_inliers)) {
      result.failure = InitFailure::kPnpFailed;
      result.value = pnp_inliers;
      result.limit = options.min_pnp_inliers;
      return result;
    }
    posed[k] = true;
    TriangulateMore(frames, posed, T_v_c, options, {}, &points);
  }
  // 4. All of it adjusted together.
  std::vector<SightingError> errors;
  result.reprojection_rms_px =
      BundleAdjust(frames, l, options, &T_v_c, &points, &errors);
  result.sightings = static_cast<int>(errors.size());
  // 5. Outlier sightings out, the rest adjusted again (ClassifySightings:
  // a point with mostly bad sightings goes whole, its anchor's too).
  std::vector<SfmFrame> kept;  // frames without the removed sightings
  for (int round = 0; round < options.outlier_rounds; ++round) {
    std::vector<std::pair<int, int64_t>> out;
    for (size_t b = 0; b < errors.size();) {
      size_t e = b;
      std::vector<double> px;
      for (; e < errors.size() && errors[e].id == errors[b].id; ++e) {
        px.push_back(errors[e].px);
      }
      const int64_t id = errors[b].id;
      const SightingVerdict verdict =
          ClassifySightings(px, options.outlier_threshold_px);
      // A point the adjustment put behind its anchor is gone already.
      if (points.count(id) > 0 && verdict.whole) {
        points.erase(id);
        result.outlier_sightings += static_cast<int>(e - b);
        const std::vector<SfmFrame>& current = kept.empty() ? frames : kept;
        for (int k = 0; k < n; ++k) {
          if (current[k].xy.count(id) > 0) out.emplace_back(k, id);
        }
      } else if (points.count(id) > 0) {
        for (int i : verdict.bad) out.emplace_back(errors[b + i].frame, id);
        result.outlier_sightings += static_cast<int>(verdict.bad.size());
      }
      b = e;
    }
    if (out.empty()) break;
    if (kept.empty()) kept = frames;
    for (const auto& [k, id] : out) kept[k].xy.erase(id);
    result.removed.insert(result.removed.end(), out.begin(), out.end());
    result.reprojection_rms_px =
        BundleAdjust(kept, l, options, &T_v_c, &points, &errors);
  }
  result.outlier_share =
      result.sightings > 0
          ? static_cast<double>(result.outlier_sightings) / result.sightings
          : 0.0;
  // A reconstruction that is mostly outliers is a wrong one: refused, as is
  // one left with fewer points than its reference pair needed inliers.
  if (!(result.outlier_share <= options.max_outlier_share)) {
    result.failure = InitFailure::kTooManyOutliers;
    result.value = result.outlier_share;
    result.limit = options.max_outlier_share;
    return result;
  }
  if (!result.removed.empty() &&
      static_cast<int>(points.size()) < options.min_inliers) {
    result.failure = InitFailure::kFewPointsLeft;
    result.value = static_cast<double>(points.size());
    result.limit = options.min_inliers;
    return result;
  }
  if (!(result.reprojection_rms_px <= options.max_reprojection_rms_px)) {
    result.failure = InitFailure::kReprojectionError;
    result.value = result.reprojection_rms_px;
    result.limit = options.max_reprojection_rms_px;
    return result;
  }
  result.T_v_c = std::move(T_v_c);
  result.points_v = std::move(points);
  return result;
}

}  // namespace vio
