#include "dataset/sim_features.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vio {
namespace {

// Closer than this a landmark is not tracked (it would fill the image) [m].
constexpr double kMinDepth = 0.2;
// Noise-free pixels stay this many noise sigmas inside the image, so that a
// noisy pixel still lies in it (plus 1 px for sigma = 0).
constexpr double kBorderSigmas = 4.0;

// The largest |xy| of the image's corners and edge midpoints, undistorted,
// plus 5 %: beyond it a distortion polynomial may fold points back into the
// image, which a real lens never does.
double MaxRadius(const CameraModel& camera) {
  const CameraCalibration& c = camera.calibration();
  const double w = c.width - 1.0, h = c.height - 1.0;
  double r = 0.0;
  for (const Eigen::Vector2d& uv :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0), Eigen::Vector2d(0, h),
        Eigen::Vector2d(w, h), Eigen::Vector2d(w / 2, 0),
        Eigen::Vector2d(0, h / 2), Eigen::Vector2d(w, h / 2),
        Eigen::Vector2d(w / 2, h)}) {
    Eigen::Vector2d xy;
    if (camera.PixelToNormalized(uv, &xy)) r = std::max(r, xy.norm());
  }
  return 1.05 * r;
}

// A grid of cells of the minimum feature distance, to test "no feature within
// d" against the 3x3 cells around a pixel.
class OccupancyGrid {
 public:
  OccupancyGrid(int width, int height, double cell)
      : cell_(std::max(cell, 1.0)),
        cols_(static_cast<int>(width / cell_) + 1),
        rows_(static_cast<int>(height / cell_) + 1),
        cells_(static_cast<size_t>(cols_) * rows_) {}

  bool Free(const Eigen::Vector2d& uv, double distance) const {
    const int cx = Col(uv), cy = Row(uv);
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, rows_ - 1); ++y) {
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, cols_ - 1); ++x) {
        for (const Eigen::Vector2d& other : cells_[y * cols_ + x]) {
          if ((other - uv).norm() < distance) return false;
        }
      }
    }
    return true;
  }
  void Add(const Eigen::Vector2d& uv) {
    cells_[Row(uv) * cols_ + Col(uv)].push_back(uv);
  }

 private:
  int Col(const Eigen::Vector2d& uv) const {
    return std::clamp(static_cast<int>(uv.x() / cell_), 0, cols_ - 1);
  }
  int Row(const Eigen::Vector2d& uv) const {
    return std::clamp(static_cast<int>(uv.y() / cell_), 0, rows_ - 1);
  }
  double cell_;
  int cols_, rows_;
  std::vector<std::vector<Eigen::Vector2d>> cells_;
};

}  // namespace

std::vector<Eigen::Vector3d> MakeRoomLandmarks(const SimRoomOptions& room,
                                               std::mt19937* rng) {
  const double lx = 2.0 * room.half_length_x_m, ly = 2.0 * room.half_width_y_m;
  const double h = room.height_m;
  // Faces: floor, ceiling, walls x = -+, walls y = -+; their areas.
  const double areas[6] = {lx * ly, lx * ly, ly * h, ly * h, lx * h, lx * h};
  std::discrete_distribution<int> face(std::begin(areas), std::end(areas));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> landmarks;
  landmarks.reserve(room.landmarks);
  for (int i = 0; i < room.landmarks; ++i) {
    const int f = face(*rng);
    const double a = unit(*rng), b = unit(*rng);
    const double x = (a - 0.5) * lx, y = (b - 0.5) * ly;
    switch (f) {
      case 0:
        landmarks.emplace_back(x, y, 0.0);
        break;
      case 1:
        landmarks.emplace_back(x, y, h);
        break;
      case 2:
        landmarks.emplace_back(-0.5 * lx, y, a * h);
        break;
      case 3:
        landmarks.emplace_back(0.5 * lx, y, a * h);
        break;
      case 4:
        landmarks.emplace_back(x, -0.5 * ly, b * h);
        break;
      default:
        landmarks.emplace_back(x, 0.5 * ly, b * h);
        break;
    }
  }
  return landmarks;
}

SimFeatureTracker::SimFeatureTracker(
    const SimCameraOptions& options,
    const std::vector<Eigen::Vector3d>* landmarks_w, uint32_t seed)
    : options_(options),
      landmarks_w_(landmarks_w),
      border_(kBorderSigmas * options.pixel_noise_px + 1.0),
      rng_(seed) {
  cameras_.emplace_back(options.cam0);
  if (options.stereo) cameras_.emplace_back(options.cam1);
  for (const CameraModel& camera : cameras_) {
    max_radius_.push_back(MaxRadius(camera));
  }
}

bool SimFeatureTracker::Visible(int camera, const Eigen::Quaterniond& q_c_w,
                                const Eigen::Vector3d& p_c_w, int l,
                                Eigen::Vector2d* uv) const {
  const Eigen::Vector3d p_c = q_c_w * (*landmarks_w_)[l] + p_c_w;
  if (p_c.z() < kMinDepth) return false;
  if (p_c.head<2>().norm() > max_radius_[camera] * p_c.z()) return false;
  if (!cameras_[camera].Project(p_c, uv)) return false;
  const CameraCalibration& c = cameras_[camera].calibration();
  return uv->x() >= border_ && uv->y() >= border_ &&
         uv->x() <= c.width - 1.0 - border_ &&
         uv->y() <= c.height - 1.0 - border_;
}

Eigen::Vector2d SimFeatureTracker::Measure(int camera,
                                           const Eigen::Vector2d& uv,
                                           bool* outlier) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  *outlier = unit(rng_) < options_.outlier_fraction;
  if (*outlier) {
    const CameraCalibration& c = cameras_[camera].calibration();
    return {unit(rng_) * (c.width - 1.0), unit(rng_) * (c.height - 1.0)};
  }
  if (options_.pixel_noise_px <= 0.0) return uv;
  std::normal_distribution<double> noise(0.0, options_.pixel_noise_px);
  const double du = noise(rng_);
  const double dv = noise(rng_);
  return uv + Eigen::Vector2d(du, dv);
}

void SimFeatureTracker::DetectNew(
    const std::vector<std::pair<int, Eigen::Vector2d>>& visible,
    const std::vector<bool>& taken) {
  const CameraCalibration& c = cameras_[0].calibration();
  const double d = options_.min_feature_distance_px;
  OccupancyGrid grid(c.width, c.height, d);
  for (const ActiveTrack& track : tracks_) grid.Add(track.uv);
  // Random order stands in for the detector's corner ranking.
  std::vector<int> order(visible.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::shuffle(order.begin(), order.end(), rng_);
  for (int i : order) {
    if (static_cast<int>(tracks_.size()) >= options_.max_features_per_frame) {
      break;
    }
    const auto& [l, uv] = visible[i];
    if (taken[l] || !grid.Free(uv, d)) continue;
    grid.Add(uv);
    const int64_t id = static_cast<int64_t>(landmark_of_feature_.size());
    landmark_of_feature_.push_back(l);
    tracks_.push_back(ActiveTrack{id, l, uv});
  }
}

void SimFeatureTracker::Track(int64_t t_ns, const Eigen::Quaterniond& q_w_b,
                              const Eigen::Vector3d& p_w_b, FeatureFrame* frame,
                              std::vector<bool>* is_outlier) {
  frame->t_ns = t_ns;
  // T_c_w = (T_w_b T_b_c)^-1 per camera.
  std::vector<Eigen::Quaterniond> q_c_w;
  std::vector<Eigen::Vector3d> p_c_w;
  for (const CameraModel& camera : cameras_) {
    const CameraCalibration& c = camera.calibration();
    const Eigen::Quaterniond q_w_c = q_w_b * c.q_b_c;
    const Eigen::Vector3d p_w_c = q_w_b * c.t_b_c + p_w_b;
    q_c_w.push_back(q_w_c.conjugate());
    p_c_w.push_back(-(q_w_c.conjugate() * p_w_c));
  }
  // Continue the tracks that stay in view and are not dropped. A landmark
  // whose track ended this frame is not re-detected in the same frame.
  std::vector<bool> taken(landmarks_w_->size(), false);
  std::bernoulli_distribution drop(options_.track_drop_probability);
  std::vector<ActiveTrack> kept;
  for (ActiveTrack track : tracks_) {
    taken[track.landmark] = true;
    if (!Visible(0, q_c_w[0], p_c_w[0], track.landmark, &track.uv)) continue;
    if (drop(rng_)) continue;
    kept.push_back(track);
  }
  tracks_ = std::move(kept);
  if (static_cast<int>(tracks_.size()) < options_.max_features_per_frame) {
    std::vector<std::pair<int, Eigen::Vector2d>> visible;
    for (int l = 0; l < static_cast<int>(landmarks_w_->size()); ++l) {
      Eigen::Vector2d uv;
      if (!taken[l] && Visible(0, q_c_w[0], p_c_w[0], l, &uv)) {
        visible.emplace_back(l, uv);
      }
    }
    DetectNew(visible, taken);
  }
  for (int camera = 0; camera < static_cast<int>(cameras_.size()); ++camera) {
    for (const ActiveTrack& track : tracks_) {
      Eigen::Vector2d uv = track.uv;
      if (camera > 0 &&
          !Visible(camera, q_c_w[camera], p_c_w[camera], track.landmark, &uv)) {
        continue;
      }
      FeatureObservation obs;
      obs.feature_id = track.feature_id;
      obs.camera = camera;
      bool outlier = false;
      obs.uv = Measure(camera, uv, &outlier);
      frame->observations.push_back(obs);
      is_outlier->push_back(outlier);
    }
  }
}

}  // namespace vio
