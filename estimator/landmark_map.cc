#include "estimator/landmark_map.h"

#include <algorithm>
#include <cmath>

namespace vio {
namespace {

bool Usable(const Landmark& l) {
  return l.triangulated && l.HasAnchor() && l.inverse_depth > 0.0 &&
         std::isfinite(l.inverse_depth);
}

// The landmark's world position and its triangulation angle: the largest
// angle at the point between two of the rays from its sightings' camera
// centres (acos of the smallest cosine between unit rays).
bool Map(const Landmark& l, const CameraPoseFn& T_w_c, MappedLandmark* out) {
  out->p_w = FeatureManager::WorldPoint(l, T_w_c);
  if (!out->p_w.allFinite()) return false;
  std::vector<Eigen::Vector3d> rays;
  for (const Sighting& s : l.sightings) {
    const Eigen::Vector3d ray =
        out->p_w - T_w_c(s.frame_id, s.camera).translation();
    if (ray.norm() > 0.0) rays.push_back(ray.normalized());
  }
  double min_cos = 1.0;
  for (size_t i = 0; i < rays.size(); ++i) {
    for (size_t j = i + 1; j < rays.size(); ++j) {
      min_cos = std::min(min_cos, rays[i].dot(rays[j]));
    }
  }
  out->parallax_deg = std::acos(std::clamp(min_cos, -1.0, 1.0)) * 180.0 / M_PI;
  out->sightings = static_cast<int>(l.sightings.size());
  return true;
}

// Keeps the better triangulated of the stored and the new position: once a
// landmark's first sightings have left the window, its later records rest
// on fewer of them.
void Keep(int64_t id, const MappedLandmark& m,
          std::map<int64_t, MappedLandmark>* map) {
  const auto it = map->find(id);
  if (it == map->end() || m.parallax_deg >= it->second.parallax_deg) {
    (*map)[id] = m;
  }
}

}  // namespace

void LandmarkMap::RecordAnchoredIn(const FeatureManager& features,
                                   int64_t frame_id,
                                   const CameraPoseFn& T_w_c) {
  for (const auto& [id, landmark] : features.landmarks()) {
    if (!Usable(landmark) || landmark.anchor().frame_id != frame_id) continue;
    MappedLandmark m;
    if (Map(landmark, T_w_c, &m)) Keep(id, m, &recorded_);
  }
}

void LandmarkMap::Retire(const FeatureManager& features,
                         const std::vector<int64_t>& newest_ids) {
  for (auto it = recorded_.begin(); it != recorded_.end();) {
    const int64_t id = it->first;
    if (features.landmarks().count(id) != 0 ||
        std::binary_search(newest_ids.begin(), newest_ids.end(), id)) {
      ++it;
      continue;
    }
    Keep(id, it->second, &finished_);
    it = recorded_.erase(it);
  }
}

std::map<int64_t, MappedLandmark> LandmarkMap::TakeFinished() {
  std::map<int64_t, MappedLandmark> taken;
  taken.swap(finished_);
  return taken;
}

std::map<int64_t, MappedLandmark> LandmarkMap::WithWindow(
    const FeatureManager& features, const CameraPoseFn& T_w_c) const {
  // In the order the records were made: finished ones first.
  std::map<int64_t, MappedLandmark> all = finished_;
  for (const auto& [id, m] : recorded_) Keep(id, m, &all);
  for (const auto& [id, landmark] : features.landmarks()) {
    MappedLandmark m;
    if (Usable(landmark) && Map(landmark, T_w_c, &m)) Keep(id, m, &all);
  }
  return all;
}

}  // namespace vio
