#include "estimator/landmark_map.h"

#include <algorithm>
#include <cmath>

namespace vio {
namespace {

// A world point without sightings is an orphan about to be released (an
// outlier removed): its earlier record stands.
bool Usable(const Landmark& l) {
  if (l.world_point) {
    return !l.sightings.empty() &&
           Eigen::Vector3d(l.p_w.data()).allFinite();
  }
  return l.triangulated && l.HasAnchor() && l.inverse_depth > 0.0 &&
         std::isfinite(l.inverse_depth);
}

// The largest angle [deg] at p_w between the rays from `centres` (acos of
// the smallest cosine between unit rays).
template <typename Centres>
double LargestAngleDeg(const Eigen::Vector3d& p_w, const Centres& centres) {
  std::vector<Eigen::Vector3d> rays;
  for (const Eigen::Vector3d& c : centres) {
    const Eigen::Vector3d ray = p_w - c;
    if (ray.norm() > 0.0) rays.push_back(ray.normalized());
  }
  double min_cos = 1.0;
  for (size_t i = 0; i < rays.size(); ++i) {
    for (size_t j = i + 1; j < rays.size(); ++j) {
      min_cos = std::min(min_cos, rays[i].dot(rays[j]));
    }
  }
  return std::acos(std::clamp(min_cos, -1.0, 1.0)) * 180.0 / M_PI;
}

// The landmark's world position and its triangulation angle: the largest
// angle at the point between two of the rays from its sightings' camera
// centres (acos of the smallest cosine between unit rays).
bool Map(const Landmark& l, const CameraPoseFn& T_w_c, MappedLandmark* out) {
  out->p_w = FeatureManager::WorldPoint(l, T_w_c);
  if (!out->p_w.allFinite()) return false;
  std::vector<Eigen::Vector3d> centres;
  for (const Sighting& s : l.sightings) {
    centres.push_back(T_w_c(s.frame_id, s.camera).translation());
  }
  out->parallax_deg = LargestAngleDeg(out->p_w, centres);
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

// The better triangulated of a and b (b on a tie, as Keep).
const MappedLandmark& Wider(const MappedLandmark& a, const MappedLandmark& b) {
  return b.parallax_deg >= a.parallax_deg ? b : a;
}

}  // namespace

MappedLandmark LandmarkMap::Record::Best() const {
  if (!has_closed) return live;
  if (!has_live) return closed;
  return Wider(closed, live);
}

void LandmarkMap::Add(const Landmark& l, const CameraPoseFn& T_w_c,
                      Record* r) {
  if (l.world_point) {
    const Eigen::Vector3d p_w(l.p_w.data());
    if (!p_w.allFinite()) return;
    if (!r->live_is_point) {
      // Converted: the track's earlier records (a restart's, or one made
      // when a conversion was refused) become the closed ones.
      if (r->has_live) {
        r->closed = r->has_closed ? Wider(r->closed, r->live) : r->live;
        r->has_closed = true;
      }
      r->centres.clear();
    }
    for (const Sighting& s : l.sightings) {
      r->centres[{s.frame_id, s.camera}] =
          T_w_c(s.frame_id, s.camera).translation();
    }
    std::vector<Eigen::Vector3d> centres;
    for (const auto& [key, c] : r->centres) centres.push_back(c);
    r->live.p_w = p_w;
    r->live.parallax_deg = LargestAngleDeg(p_w, centres);
    r->live.sightings = static_cast<int>(centres.size());
    r->live_is_point = true;
    r->has_live = true;
    return;
  }
  MappedLandmark m;
  if (!Map(l, T_w_c, &m)) return;
  if (r->live_is_point) {
    // The point was capped or released and its track restarted.
    r->closed = r->has_closed ? Wider(r->closed, r->live) : r->live;
    r->has_closed = true;
    r->live = m;
    r->live_is_point = false;
    r->centres.clear();
  } else if (!r->has_live || m.parallax_deg >= r->live.parallax_deg) {
    r->live = m;
  }
  r->has_live = true;
}

void LandmarkMap::RecordWorldPoints(const FeatureManager& features,
                                    const CameraPoseFn& T_w_c,
                                    const std::vector<int64_t>& ids) {
  for (const int64_t id : ids) {
    const auto l = features.landmarks().find(id);
    if (l == features.landmarks().end()) continue;
    const Landmark& landmark = l->second;
    if (!landmark.world_point || !Usable(landmark)) continue;
    const auto it = recorded_.try_emplace(id).first;
    Add(landmark, T_w_c, &it->second);
    if (!it->second.has_live) recorded_.erase(it);
  }
}

void LandmarkMap::RecordAnchoredIn(const FeatureManager& features,
                                   int64_t frame_id,
                                   const CameraPoseFn& T_w_c) {
  for (const auto& [id, landmark] : features.landmarks()) {
    if (!Usable(landmark) || !landmark.HasAnchor() ||
        landmark.anchor().frame_id != frame_id) {
      continue;
    }
    const auto it = recorded_.try_emplace(id).first;
    Add(landmark, T_w_c, &it->second);
    if (!it->second.has_live) recorded_.erase(it);
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
    Keep(id, it->second.Best(), &finished_);
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
  // A live world point's record is replaced by the point as it is now.
  const auto live_point = [&features](int64_t id) {
    const auto it = features.landmarks().find(id);
    return it != features.landmarks().end() && it->second.world_point &&
           Usable(it->second);
  };
  for (const auto& [id, r] : recorded_) {
    if (!live_point(id)) Keep(id, r.Best(), &all);
  }
  for (const auto& [id, landmark] : features.landmarks()) {
    if (!Usable(landmark)) continue;
    if (landmark.world_point) {
      const auto it = recorded_.find(id);
      Record r = it != recorded_.end() ? it->second : Record();
      Add(landmark, T_w_c, &r);
      if (r.has_live) Keep(id, r.Best(), &all);
      continue;
    }
    MappedLandmark m;
    if (Map(landmark, T_w_c, &m)) Keep(id, m, &all);
  }
  return all;
}

}  // namespace vio
