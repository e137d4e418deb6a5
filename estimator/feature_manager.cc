#include "estimator/feature_manager.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

bool Before(const Sighting& a, const Sighting& b) {
  return a.frame_id < b.frame_id ||
         (a.frame_id == b.frame_id && a.camera < b.camera);
}

const Sighting* FindSighting(const Landmark& l, int64_t frame_id, int camera) {
  for (const Sighting& s : l.sightings) {
    if (s.frame_id == frame_id && s.camera == camera) return &s;
  }
  return nullptr;
}

}  // namespace

FrameAddStats FeatureManager::AddFrame(
    int64_t frame_id, const std::vector<FeatureObservation>& observations) {
  if (frame_id <= last_frame_id_) {
    throw std::invalid_argument("FeatureManager::AddFrame: frame id " +
                                std::to_string(frame_id) + " does not follow " +
                                std::to_string(last_frame_id_));
  }
  last_frame_id_ = frame_id;
  FrameAddStats stats;
  std::set<std::pair<int64_t, int>> seen;
  for (const FeatureObservation& o : observations) {
    const bool valid = o.camera >= 0 && o.camera < num_cameras_ &&
                       o.xy.allFinite() && o.velocity.allFinite() &&
                       seen.insert({o.feature_id, o.camera}).second;
    if (!valid) {
      ++stats.skipped;
      continue;
    }
    Landmark& l = landmarks_[o.feature_id];
    l.feature_id = o.feature_id;
    if (o.camera == 0 && !l.sightings.empty() &&
        l.sightings.back().frame_id < frame_id) {
      ++stats.tracked;
    }
    Sighting s{frame_id, o.camera, o.xy, o.velocity};
    // Observations arrive camera by camera; keep (frame, camera) order.
    l.sightings.insert(
        std::upper_bound(l.sightings.begin(), l.sightings.end(), s, Before), s);
    ++stats.added;
  }
  return stats;
}

double FeatureManager::MedianParallax(int64_t frame_a, int64_t frame_b,
                                      int* common) const {
  std::vector<double> parallax;
  for (const auto& [id, l] : landmarks_) {
    const Sighting* a = FindSighting(l, frame_a, 0);
    const Sighting* b = FindSighting(l, frame_b, 0);
    if (a == nullptr || b == nullptr) continue;
    parallax.push_back((a->xy - b->xy).norm());
  }
  *common = static_cast<int>(parallax.size());
  if (parallax.empty()) return 0.0;
  const auto mid = parallax.begin() + parallax.size() / 2;
  std::nth_element(parallax.begin(), mid, parallax.end());
  return *mid;
}

Eigen::Vector3d FeatureManager::WorldPoint(const Landmark& landmark,
                                           const CameraPoseFn& T_w_c) {
  if (landmark.world_point) return Eigen::Vector3d(landmark.p_w.data());
  const Sighting& a = landmark.anchor();
  return T_w_c(a.frame_id, a.camera) *
         (a.xy.homogeneous() / landmark.inverse_depth);
}

void FeatureManager::RemoveFrame(int64_t frame_id, const CameraPoseFn& T_w_c) {
  for (auto it = landmarks_.begin(); it != landmarks_.end();) {
    Landmark& l = it->second;
    // Only a triangulated landmark anchored here has a point to carry over.
    const bool carry =
        l.triangulated && l.HasAnchor() && l.anchor().frame_id == frame_id;
    const Eigen::Vector3d p_w =
        carry ? WorldPoint(l, T_w_c) : Eigen::Vector3d::Zero();
    l.sightings.erase(std::remove_if(l.sightings.begin(), l.sightings.end(),
                                     [frame_id](const Sighting& s) {
                                       return s.frame_id == frame_id;
                                     }),
                      l.sightings.end());
    if (l.sightings.empty() && !l.world_point) {
      it = landmarks_.erase(it);
      continue;
    }
    if (carry) {
      // rho_new = 1 / z of the point in the new anchor camera.
      l.triangulated = false;
      l.inverse_depth = 0.0;
      if (l.HasAnchor()) {
        const Sighting& a = l.anchor();
        const double depth = (T_w_c(a.frame_id, a.camera).inverse() * p_w).z();
        if (std::isfinite(depth) && depth > 0.0) {
          l.triangulated = true;
          l.inverse_depth = 1.0 / depth;
        }
      }
    }
    ++it;
  }
}

void FeatureManager::RemoveSighting(int64_t feature_id, int64_t frame_id,
                                    int camera) {
  const auto it = landmarks_.find(feature_id);
  if (it == landmarks_.end()) return;
  Landmark& l = it->second;
  const int anchor = l.AnchorIndex();
  for (size_t i = 0; i < l.sightings.size(); ++i) {
    if (l.sightings[i].frame_id != frame_id ||
        l.sightings[i].camera != camera) {
      continue;
    }
    if (static_cast<int>(i) == anchor && !l.world_point) {
      l.triangulated = false;
      l.inverse_depth = 0.0;
    }
    l.sightings.erase(l.sightings.begin() + i);
    break;
  }
  if (l.sightings.empty() && !l.world_point) landmarks_.erase(it);
}

void FeatureManager::RemoveLandmark(int64_t feature_id) {
  const auto it = landmarks_.find(feature_id);
  if (it == landmarks_.end()) return;
  if (it->second.world_point) {
    it->second.sightings.clear();
  } else {
    landmarks_.erase(it);
  }
}

std::vector<int64_t> FeatureManager::OrphanPoints() const {
  std::vector<int64_t> ids;
  for (const auto& [id, l] : landmarks_) {
    if (l.world_point && l.sightings.empty()) ids.push_back(id);
  }
  return ids;
}

int FeatureManager::TriangulateNew(const CameraPoseFn& T_w_c,
                                   const TriangulationOptions& options) {
  int count = 0;
  std::vector<TriangulationView> views;
  for (auto& [id, l] : landmarks_) {
    const int anchor = l.AnchorIndex();
    if (l.triangulated || l.world_point || anchor < 0 ||
        static_cast<int>(l.sightings.size()) < options.min_observations) {
      continue;
    }
    // The anchor first: Triangulate checks its depth range on views[0].
    views.clear();
    const Sighting& a = l.sightings[anchor];
    views.push_back({T_w_c(a.frame_id, a.camera), a.xy});
    for (int i = 0; i < static_cast<int>(l.sightings.size()); ++i) {
      const Sighting& s = l.sightings[i];
      if (i != anchor) views.push_back({T_w_c(s.frame_id, s.camera), s.xy});
    }
    Eigen::Vector3d p_w;
    double depth = 0.0;
    if (Triangulate(views, options, &p_w, &depth) == TriangulationStatus::kOk) {
      l.triangulated = true;
      l.inverse_depth = 1.0 / depth;
      ++count;
    }
  }
  return count;
}

KeyframeDecision DecideKeyframe(const FeatureManager& features,
                                int64_t last_keyframe_id, int64_t new_frame_id,
                                double focal_px,
                                const KeyframeOptions& options) {
  KeyframeDecision d;
  d.parallax_px =
      focal_px * features.MedianParallax(last_keyframe_id, new_frame_id,
                                         &d.common_features);
  d.is_keyframe = d.common_features < options.min_tracked_features ||
                  d.parallax_px >= options.min_parallax_px;
  return d;
}

}  // namespace vio
