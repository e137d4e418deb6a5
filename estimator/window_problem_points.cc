// The world points of the window problem (landmarks.reanchored_tracks
// keep_point): their factors in the step's problem, and their part in the
// marginalisation of the oldest frame. Why: with inverse depths (reuse) a
// track's remaining sightings are folded into the prior again each time its
// anchor leaves, about five times per sighting, which makes the estimator
// overconfident (docs/recorded_flights.md, "Consistency"); holding the track
// as a point the prior keeps folds each sighting once and keeps the track's
// link to its past.

#include <algorithm>

#include "estimator/window_problem.h"
#include "factors/timed_world_point_factor.h"
#include "factors/world_point_factor.h"

namespace vio {

std::unique_ptr<ceres::CostFunction> WindowProblem::WorldPointFactor(
    Landmark& l, const Sighting& s, const TangentJacobians** tangent,
    std::vector<double*>* blocks) const {
  const double sqrt_info =
      settings_.visual.SqrtInformation(settings_.focal_px[s.camera]);
  const double* first =
      settings_.point_first_estimates ? l.p_w_first.data() : nullptr;
  WindowFrame& frame = *window_->Find(s.frame_id);
  *blocks = {frame.pose.data(), window_->extrinsics[s.camera].data(),
             l.p_w.data()};
  if (!settings_.estimate_time_offset) {
    auto factor =
        std::make_unique<WorldPointReprojectionFactor>(s.xy, sqrt_info, first);
    *tangent = factor.get();
    return factor;
  }
  // The sighting shifted along its own camera's image velocity, predicted
  // from the frame's current state and the point's current estimate (not
  // p_w_first: the velocity moves the residual, which is taken at the
  // current estimate; factors/timed_world_point_factor.h). Camera 1 saw the
  // point at the same instant as camera 0, so the same t_d - t_d_k shifts it.
  const Eigen::Vector3d p_c =
      window_->T_w_c(s.frame_id, s.camera).inverse() *
      Eigen::Vector3d(l.p_w.data());
  auto factor = std::make_unique<TimedWorldPointReprojectionFactor>(
      TimedObservation{s.xy, MotionVelocity(frame, p_c, s.camera),
                       frame.t_d_at_stamp},
      sqrt_info, first);
  *tangent = factor.get();
  blocks->push_back(&window_->t_d);
  return factor;
}

int WindowProblem::AddWorldPoints() {
  int used = 0;
  for (auto& [id, l] : features_->landmarks()) {
    if (!l.world_point || l.sightings.empty()) continue;
    for (const Sighting& s : l.sightings) {
      Residual r;
      r.loss = loss_.get();
      r.feature_id = l.feature_id;
      r.point = l.p_w.data();
      r.target_frame = s.frame_id;
      r.target_camera = s.camera;
      r.owned = WorldPointFactor(l, s, &r.tangent, &r.blocks);
      r.cost = r.owned.get();
      AddResidual(std::move(r));
      ++num_visual_;
    }
    ++used;
  }
  return used;
}

std::set<int64_t> WindowProblem::ConvertLeavingTracks(
    const OutlierReport& excluded) const {
  const int64_t oldest = window_->frames.front()->id;
  std::set<int64_t> converted;
  for (const Residual& r : residuals_) {
    if (r.rho == nullptr || r.anchor_frame != oldest ||
        converted.count(r.feature_id) != 0 || excluded.Involves(r.feature_id)) {
      continue;
    }
    Landmark& l = features_->landmarks().at(r.feature_id);
    const bool goes_on = std::any_of(
        l.sightings.begin(), l.sightings.end(),
        [oldest](const Sighting& s) { return s.frame_id != oldest; });
    if (!goes_on || !(l.inverse_depth > 0.0)) continue;
    const Eigen::Vector3d p_w =
        FeatureManager::WorldPoint(l, [this](int64_t frame, int camera) {
          return window_->T_w_c(frame, camera);
        });
    if (!p_w.allFinite()) continue;
    std::copy(p_w.data(), p_w.data() + 3, l.p_w.begin());
    l.p_w_first = l.p_w;
    l.world_point = true;
    l.triangulated = false;
    converted.insert(r.feature_id);
  }
  return converted;
}

std::vector<int64_t> WindowProblem::CapWorldPoints(
    const std::vector<int64_t>& staying, const OutlierReport& excluded) const {
  const int excess =
      static_cast<int>(staying.size()) - settings_.max_points;
  if (settings_.max_points <= 0 || excess <= 0) return {};
  // Why this order: a point leaves the window with its last sighting, so
  // the one whose last sighting is oldest would leave soonest anyway, and a
  // track the tracker has lost (not seen in the newest frame) has no future
  // sighting to link to its past; among tracks still seen, one with fewer
  // sightings holds less of the live problem. Marginalised now, such a
  // point's sightings are linearised a few steps earlier than they would
  // have been; nothing is dropped.
  struct Rank {
    int64_t last_frame;
    size_t sightings;
    int64_t id;
  };
  std::vector<Rank> candidates;
  for (const int64_t id : staying) {
    if (excluded.Involves(id)) continue;
    const Landmark& l = features_->landmarks().at(id);
    candidates.push_back({l.sightings.back().frame_id, l.sightings.size(), id});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Rank& a, const Rank& b) {
              if (a.last_frame != b.last_frame) {
                return a.last_frame < b.last_frame;
              }
              if (a.sightings != b.sightings) return a.sightings < b.sightings;
              return a.id < b.id;
            });
  std::vector<int64_t> capped;
  for (int k = 0; k < excess && k < static_cast<int>(candidates.size()); ++k) {
    capped.push_back(candidates[k].id);
  }
  std::sort(capped.begin(), capped.end());
  return capped;
}

void WindowProblem::AddPointMarginalization(
    const OutlierReport& excluded, const std::set<int64_t>& converted,
    MarginalizationProblem* m, std::set<const double*>* touched) const {
  converted_factors_.clear();
  capped_points_.clear();
  WindowFrame& oldest = *window_->frames.front();
  // The world points left after this marginalisation: the converted ones
  // and those seen in another frame than the oldest. A world point seen in
  // no other frame leaves with this one (its factors are all among the
  // oldest frame's, folded by OldestFrameMarginalization). One with
  // outliers is about to be removed: the estimator releases it from the
  // prior then.
  std::vector<int64_t> ending;
  std::vector<int64_t> staying(converted.begin(), converted.end());
  for (const auto& [id, l] : features_->landmarks()) {
    if (!l.world_point || l.sightings.empty() || converted.count(id) != 0) {
      continue;
    }
    const bool ends = std::all_of(
        l.sightings.begin(), l.sightings.end(),
        [&oldest](const Sighting& s) { return s.frame_id == oldest.id; });
    if (!ends) {
      staying.push_back(id);
    } else if (!excluded.Involves(id)) {
      ending.push_back(id);
    }
  }
  capped_points_ = CapWorldPoints(staying, excluded);
  const std::set<int64_t> capped(capped_points_.begin(), capped_points_.end());
  // A converted track folds its oldest-frame sightings (all of them when
  // capped), as world-point factors at its first estimate.
  for (const int64_t id : converted) {
    Landmark& l = features_->landmarks().at(id);
    const bool all = capped.count(id) != 0;
    for (const Sighting& s : l.sightings) {
      if (!all && s.frame_id != oldest.id) continue;
      // As AddWorldPoints builds it: timed (on t_d, a kept block) when the
      // time offset is estimated.
      const TangentJacobians* tangent = nullptr;
      std::vector<double*> blocks;
      converted_factors_.push_back(WorldPointFactor(l, s, &tangent, &blocks));
      m->residual_blocks.push_back(
          {converted_factors_.back().get(), loss_.get(), blocks});
      for (double* b : blocks) {
        if (b != l.p_w.data()) touched->insert(b);
      }
    }
    m->parameter_blocks.push_back({l.p_w.data(), 3, nullptr, false});
  }
  // A capped world point of earlier steps: its factors in the other frames
  // (those in the oldest are folded already).
  for (const Residual& r : residuals_) {
    if (r.point == nullptr || capped.count(r.feature_id) == 0 ||
        converted.count(r.feature_id) != 0 || r.target_frame == oldest.id) {
      continue;
    }
    m->residual_blocks.push_back({r.cost, r.loss, r.blocks});
    touched->insert(r.blocks.begin(), r.blocks.end());
  }
  for (const int64_t id : ending) {
    m->marginalized.push_back(features_->landmarks().at(id).p_w.data());
  }
  for (const int64_t id : capped_points_) {
    m->marginalized.push_back(features_->landmarks().at(id).p_w.data());
  }
}

}  // namespace vio
