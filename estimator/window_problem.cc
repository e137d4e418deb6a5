#include "estimator/window_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "estimator/image_velocity.h"
#include "estimator/sighting_outliers.h"
#include "estimator/window_solver.h"
#include "factors/imu_factor.h"
#include "factors/reprojection_factor.h"
#include "factors/robust_kernel.h"
#include "factors/stereo_reprojection_factor.h"
#include "factors/timed_reprojection_factor.h"

namespace vio {
namespace {

ceres::Problem::Options ProblemOptions() {
  ceres::Problem::Options o;
  o.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  // Blocks are never removed within a step; skip Ceres' reverse index.
  o.enable_fast_removal = false;
  return o;
}

// Notes the factor's tangent-space Jacobians in the residual and hands the
// factor on as a plain cost function.
template <typename Factor>
std::unique_ptr<ceres::CostFunction> Tangent(std::unique_ptr<Factor> factor,
                                             const TangentJacobians** tangent) {
  *tangent = factor.get();
  return factor;
}

}  // namespace

WindowProblem::WindowProblem(Window* window, FeatureManager* features,
                             const WindowProblemSettings& settings)
    : window_(window),
      features_(features),
      settings_(settings),
      loss_(MakeLossFunction(settings.visual.robust_kernel)) {
  for (auto& f : window_->frames) {
    AddBlock(f->pose.data(), 7, /*pose=*/true, /*constant=*/false);
    AddBlock(f->speed_bias.data(), 9, /*pose=*/false, /*constant=*/false);
  }
  for (int c = 0; c < window_->num_cameras; ++c) {
    AddBlock(window_->extrinsics[c].data(), 7, /*pose=*/true,
             !settings_.estimate_extrinsics);
  }
  if (settings_.keep_points) {
    // The prior may hold them: present even without sightings.
    for (auto& [id, l] : features_->landmarks()) {
      if (l.world_point) AddBlock(l.p_w.data(), 3, false, false);
    }
  }
  if (settings_.estimate_time_offset) {
    AddBlock(&window_->t_d, 1, /*pose=*/false, /*constant=*/false);
    // Unobservable while the camera barely moves: keep it to a plausible
    // range instead of letting it wander.
    blocks_[&window_->t_d].bound = settings_.max_time_offset_s;
  }
}

void WindowProblem::AddBlock(double* values, int size, bool pose,
                             bool constant) {
  const ceres::Manifold* manifold = pose ? &pose_manifold_ : nullptr;
  BlockInfo& info = blocks_[values];
  info.size = size;
  info.manifold = manifold;
  info.constant = constant;
  info.index = static_cast<int>(block_order_.size());
  block_order_.push_back(values);
}

void WindowProblem::AddResidual(Residual residual) {
  residual.first_index = static_cast<int>(indices_.size());
  for (const double* values : residual.blocks) {
    indices_.push_back(blocks_.at(values).index);
  }
  residuals_.push_back(std::move(residual));
}

void WindowProblem::AddPrior(const MarginalizationPrior* prior,
                             const std::vector<double*>& blocks) {
  Residual r;
  r.cost = prior;
  r.prior = prior;
  r.blocks = blocks;
  AddResidual(std::move(r));
}

bool WindowProblem::AddImuFactors() {
  std::vector<Residual> imu;
  auto& frames = window_->frames;
  for (size_t k = 1; k < frames.size(); ++k) {
    WindowFrame& i = *frames[k - 1];
    WindowFrame& j = *frames[k];
    if (!j.imu) continue;  // across an IMU gap: linked by landmarks only
    Residual r;
    try {
      r.owned = std::make_unique<ImuFactor>(j.imu->result(),
                                            settings_.gravity_magnitude);
    } catch (const std::invalid_argument&) {
      return false;
    }
    r.cost = r.owned.get();
    r.blocks = {i.pose.data(), i.speed_bias.data(), j.pose.data(),
                j.speed_bias.data()};
    r.imu_start_frame = i.id;
    imu.push_back(std::move(r));
  }
  for (Residual& r : imu) AddResidual(std::move(r));
  return true;
}

void WindowProblem::AddFrameLink(std::unique_ptr<ceres::CostFunction> cost,
                                 const std::vector<double*>& blocks,
                                 int64_t start_frame) {
  Residual r;
  r.owned = std::move(cost);
  r.cost = r.owned.get();
  r.blocks = blocks;
  r.link_start_frame = start_frame;
  AddResidual(std::move(r));
}

int WindowProblem::AddVisualFactors() {
  const int points = settings_.keep_points ? AddWorldPoints() : 0;
  const int max_landmarks =
      settings_.points_in_max_landmarks
          ? std::max(0, settings_.max_landmarks - points)
          : settings_.max_landmarks;
  // Candidates: triangulated, anchored in the window, seen again later.
  std::vector<Landmark*> candidates;
  for (auto& [id, l] : features_->landmarks()) {
    if (!l.triangulated || !l.HasAnchor()) continue;
    if (l.AnchorIndex() + 1 >= static_cast<int>(l.sightings.size())) continue;
    candidates.push_back(&l);
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Landmark* a, const Landmark* b) {
                     return a->sightings.size() > b->sightings.size();
                   });
  if (static_cast<int>(candidates.size()) > max_landmarks) {
    candidates.resize(max_landmarks);
  }
  for (Landmark* l : candidates) AddLandmark(l);
  landmarks_used_ = points + static_cast<int>(candidates.size());
  return landmarks_used_;
}

void WindowProblem::AddLandmark(Landmark* l) {
  const int anchor = l->AnchorIndex();
  const Sighting& a = l->sightings[anchor];
  double* rho = &l->inverse_depth;
  AddBlock(rho, 1, /*pose=*/false, /*constant=*/false);
  blocks_[rho].landmark = true;
  WindowFrame* frame_i = window_->Find(a.frame_id);
  double* ext0 = window_->extrinsics[0].data();
  double* ext1 = window_->extrinsics[1].data();
  // For the time offset: the anchor's point and image velocity.
  const Eigen::Vector3d p_c_i = Eigen::Vector3d(a.xy.x(), a.xy.y(), 1.0) / *rho;
  const Eigen::Vector2d velocity_i = settings_.estimate_time_offset
                                         ? MotionVelocity(*frame_i, p_c_i)
                                         : Eigen::Vector2d::Zero();
  for (size_t k = anchor + 1; k < l->sightings.size(); ++k) {
    const Sighting& s = l->sightings[k];
    const double sqrt_info =
        settings_.visual.SqrtInformation(settings_.focal_px[s.camera]);
    Residual r;
    r.loss = loss_.get();
    r.feature_id = l->feature_id;
    r.rho = rho;
    r.target_frame = s.frame_id;
    r.target_camera = s.camera;
    r.anchor_frame = a.frame_id;
    if (s.frame_id == a.frame_id) {
      r.owned = Tangent(
          std::make_unique<StereoReprojectionFactor>(a.xy, s.xy, sqrt_info),
          &r.tangent);
      r.blocks = {ext0, ext1, rho};
    } else {
      double* pose_j = window_->Find(s.frame_id)->pose.data();
      if (s.camera == 0 && settings_.estimate_time_offset) {
        const WindowFrame& frame_j = *window_->Find(s.frame_id);
        const Eigen::Vector3d p_c_j = window_->T_w_c(s.frame_id, 0).inverse() *
                                      window_->T_w_c(a.frame_id, 0) * p_c_i;
        r.owned = Tangent(
            std::make_unique<TimedReprojectionFactor>(
                TimedObservation{a.xy, velocity_i, frame_i->t_d_at_stamp},
                TimedObservation{s.xy, MotionVelocity(frame_j, p_c_j),
                                 frame_j.t_d_at_stamp},
                sqrt_info),
            &r.tangent);
        r.blocks = {frame_i->pose.data(), pose_j, ext0, rho, &window_->t_d};
      } else if (s.camera == 0) {
        r.owned =
            Tangent(std::make_unique<ReprojectionFactor>(a.xy, s.xy, sqrt_info),
                    &r.tangent);
        r.blocks = {frame_i->pose.data(), pose_j, ext0, rho};
      } else if (settings_.estimate_time_offset) {
        // Camera 1 of frame j saw the point at the same instant as its
        // camera 0: shifted along camera 1's predicted image velocity.
        const WindowFrame& frame_j = *window_->Find(s.frame_id);
        const Eigen::Vector3d p_c1_j = window_->T_w_c(s.frame_id, 1).inverse() *
                                       window_->T_w_c(a.frame_id, 0) * p_c_i;
        r.owned = std::make_unique<TimedStereoTwoFrameReprojectionFactor>(
            TimedObservation{a.xy, velocity_i, frame_i->t_d_at_stamp},
            TimedObservation{s.xy, MotionVelocity(frame_j, p_c1_j, 1),
                             frame_j.t_d_at_stamp},
            sqrt_info);
        r.blocks = {frame_i->pose.data(), pose_j, ext0, ext1, rho,
                    &window_->t_d};
      } else {
        r.owned = Tangent(std::make_unique<StereoTwoFrameReprojectionFactor>(
                              a.xy, s.xy, sqrt_info),
                          &r.tangent);
        r.blocks = {frame_i->pose.data(), pose_j, ext0, ext1, rho};
      }
    }
    r.cost = r.owned.get();
    AddResidual(std::move(r));
    ++num_visual_;
  }
}

Eigen::Vector2d WindowProblem::MotionVelocity(const WindowFrame& frame,
                                              const Eigen::Vector3d& p_c,
                                              int camera) const {
  // The current estimates (velocity, gyroscope bias, depth), not the
  // tracker's finite difference: see estimator/image_velocity.h.
  return PredictedImageVelocity(p_c, frame.T_w_b(), frame.v_w_value(),
                                frame.gyr_b - frame.b_g_value(),
                                window_->T_b_c(camera));
}

std::vector<bool> WindowProblem::TouchedBlocks() const {
  // A block no residual touches (the speed-bias of a frame placed by vision
  // across an IMU gap) is not estimated: it stays as it is.
  std::vector<bool> touched(block_order_.size(), false);
  for (const int index : indices_) touched[index] = true;
  return touched;
}

ceres::Solver::Summary WindowProblem::Solve(const SolverOptions& options,
                                            WindowSolver* solver) {
  if (options.backend == SolverBackend::kCeres) return SolveWithCeres(options);
  std::unique_ptr<WindowSolver> local;
  if (solver == nullptr) {
    local = std::make_unique<WindowSolver>();
    solver = local.get();
  }
  WindowSolverProblem& p = *solver->NewProblem();
  const std::vector<bool> touched = TouchedBlocks();
  for (size_t i = 0; i < block_order_.size(); ++i) {
    double* values = block_order_[i];
    const BlockInfo& info = blocks_.at(values);
    WindowSolverBlock b;
    b.values = values;
    b.size = info.size;
    b.manifold = info.manifold;
    b.constant = info.constant || !touched[i];
    b.eliminated = info.landmark;
    if (info.bound > 0.0) {
      b.lower = -info.bound;
      b.upper = info.bound;
    }
    p.blocks.push_back(b);
  }
  p.block_indices = indices_;
  for (const Residual& r : residuals_) {
    WindowSolverResidual w;
    w.cost = r.cost;
    w.loss = r.loss;
    w.first_block = r.first_index;
    w.num_blocks = static_cast<int>(r.blocks.size());
    w.prior = r.prior;
    w.tangent = r.tangent;
    p.residuals.push_back(w);
  }
  WindowSolverOptions o;
  o.trust_region = options.trust_region;
  o.max_iterations = options.max_iterations;
  o.max_time_s = options.max_time_s;
  o.function_tolerance = options.function_tolerance;
  o.kept_factor_pcg = options.kept_factor_pcg;
  return solver->Solve(o);
}

std::unique_ptr<ceres::Problem> WindowProblem::CeresProblem() const {
  auto problem = std::make_unique<ceres::Problem>(ProblemOptions());
  AddToCeresProblem(problem.get());
  return problem;
}

void WindowProblem::AddToCeresProblem(ceres::Problem* problem) const {
  const std::vector<bool> touched = TouchedBlocks();
  for (size_t i = 0; i < block_order_.size(); ++i) {
    double* values = block_order_[i];
    const BlockInfo& info = blocks_.at(values);
    problem->AddParameterBlock(values, info.size,
                               const_cast<ceres::Manifold*>(info.manifold));
    if (info.constant || !touched[i]) {
      problem->SetParameterBlockConstant(values);
    }
    for (int c = 0; c < info.size && info.bound > 0.0; ++c) {
      problem->SetParameterLowerBound(values, c, -info.bound);
      problem->SetParameterUpperBound(values, c, info.bound);
    }
  }
  for (const Residual& r : residuals_) {
    problem->AddResidualBlock(const_cast<ceres::CostFunction*>(r.cost),
                              const_cast<ceres::LossFunction*>(r.loss),
                              r.blocks);
  }
}

ceres::Solver::Summary WindowProblem::SolveWithCeres(
    const SolverOptions& options) {
  ceres::Problem problem(ProblemOptions());
  AddToCeresProblem(&problem);
  ceres::Solver::Options o;
  o.linear_solver_type = options.linear_solver;
  o.trust_region_strategy_type = options.trust_region;
  o.max_num_iterations = options.max_iterations;
  o.function_tolerance = options.function_tolerance;
  // Without a budget Ceres' own default (1e9 s) applies: iterations only.
  if (options.max_time_s > 0.0) {
    o.max_solver_time_in_seconds = options.max_time_s;
  }
  o.num_threads = options.num_threads;
  o.minimizer_progress_to_stdout = false;
  o.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(o, &problem, &summary);
  return summary;
}

void OutlierReport::RemoveFrom(FeatureManager* features) const {
  for (int64_t id : landmarks) features->RemoveLandmark(id);
  for (int64_t id : behind) features->RemoveLandmark(id);
  for (const BadSighting& b : sightings) {
    features->RemoveSighting(b.feature_id, b.frame_id, b.camera);
  }
}

bool OutlierReport::Involves(int64_t feature_id) const {
  for (int64_t id : landmarks) {
    if (id == feature_id) return true;
  }
  for (int64_t id : behind) {
    if (id == feature_id) return true;
  }
  for (const BadSighting& s : sightings) {
    if (s.feature_id == feature_id) return true;
  }
  return false;
}

OutlierReport WindowProblem::Outliers(double threshold_px) const {
  OutlierReport report;
  // A whitened residual r = (focal / sigma) e has |e| focal = |r| sigma px.
  // The rule is ClassifySightings' (estimator/sighting_outliers.h).
  const double max_norm = threshold_px / settings_.visual.sigma_px;
  std::vector<OutlierReport::BadSighting> tested;
  std::vector<double> norms;
  for (size_t k = 0; k < residuals_.size(); ++k) {
    const Residual& r = residuals_[k];
    if (r.feature_id < 0) continue;
    Eigen::Vector2d e;
    const bool ok = r.cost->Evaluate(r.blocks.data(), e.data(), nullptr);
    norms.push_back(ok ? e.norm() : std::numeric_limits<double>::quiet_NaN());
    tested.push_back({r.feature_id, r.target_frame, r.target_camera});
    // A landmark's residuals are consecutive.
    const bool last = k + 1 == residuals_.size() ||
                      residuals_[k + 1].feature_id != r.feature_id;
    if (!last) continue;
    // A world point has no anchor to be behind (its residuals are clamped
    // behind any camera, factors/world_point_factor.h).
    const SightingVerdict verdict = ClassifySightings(norms, max_norm);
    if (r.rho != nullptr && !(*r.rho > 0.0)) {
      report.behind.push_back(r.feature_id);
    } else if (verdict.whole) {
      report.landmarks.push_back(r.feature_id);
    } else {
      for (int i : verdict.bad) report.sightings.push_back(tested[i]);
    }
    tested.clear();
    norms.clear();
  }
  return report;
}

MarginalizationProblem WindowProblem::OldestFrameMarginalization(
    const OutlierReport& excluded) const {
  MarginalizationProblem m;
  const WindowFrame& oldest = *window_->frames.front();
  const std::set<int64_t> converted = settings_.keep_points
                                          ? ConvertLeavingTracks(excluded)
                                          : std::set<int64_t>();
  // A landmark's factors that leave with the oldest frame: an inverse
  // depth's when anchored there (unless converted), a world point's when
  // the sighting is there.
  auto leaving = [&](const Residual& r) {
    if (r.feature_id < 0 || excluded.Involves(r.feature_id)) return false;
    if (r.point != nullptr) return r.target_frame == oldest.id;
    return r.anchor_frame == oldest.id && converted.count(r.feature_id) == 0;
  };
  std::set<const double*> touched;
  for (const Residual& r : residuals_) {
    const bool prior =
        r.feature_id < 0 && r.imu_start_frame < 0 && r.link_start_frame < 0;
    const bool use = prior || r.imu_start_frame == oldest.id ||
                     r.link_start_frame == oldest.id || leaving(r);
    if (!use) continue;
    m.residual_blocks.push_back({r.cost, r.loss, r.blocks});
    touched.insert(r.blocks.begin(), r.blocks.end());
  }
  if (settings_.keep_points) {
    AddPointMarginalization(excluded, converted, &m, &touched);
  }
  // In the order the blocks entered the problem, never by address: the
  // prior's layout, and so every sum over it, must not vary between runs.
  for (double* values : block_order_) {
    if (touched.count(values) == 0) continue;
    const BlockInfo& info = blocks_.at(values);
    m.parameter_blocks.push_back(
        {values, info.size, info.manifold, info.constant});
  }
  // Across an IMU gap the oldest speed-bias may be in no factor at all.
  for (const double* block : {oldest.pose.data(), oldest.speed_bias.data()}) {
    if (touched.count(block) != 0) m.marginalized.push_back(block);
  }
  for (const Residual& r : residuals_) {
    if (r.rho != nullptr && leaving(r) &&
        (m.marginalized.empty() || m.marginalized.back() != r.rho)) {
      m.marginalized.push_back(r.rho);
    }
  }
  return m;
}

}  // namespace vio
