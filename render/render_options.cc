#include "render/render_options.h"

#include <cmath>

namespace vio {
namespace {

bool Fail(std::string* message, const std::string& text) {
  *message = text;
  return false;
}

bool Finite(double v) { return std::isfinite(v); }
bool Positive(double v) { return Finite(v) && v > 0.0; }
bool NonNegative(double v) { return Finite(v) && v >= 0.0; }

SceneBox Box(double x, double y, double sx, double sy, double sz) {
  SceneBox b;
  b.center_xy_m = {x, y};
  b.size_m = {sx, sy, sz};
  return b;
}

}  // namespace

std::vector<SceneBox> DefaultSceneBoxes() {
  return {Box(0.0, 0.0, 1.2, 1.0, 0.9), Box(5.0, 2.5, 1.0, 1.4, 1.2),
          Box(-5.0, -3.0, 1.4, 1.0, 0.8), Box(1.5, 4.3, 1.6, 0.8, 1.5),
          Box(-2.0, -4.2, 1.0, 1.0, 2.0)};
}

bool RenderOptions::Validate(std::string* message) const {
  // 16 texels/m is a blur, 2048 texels/m makes a 14 x 12 m floor 800 MB.
  if (!(Finite(texels_per_m) && texels_per_m >= 16.0 &&
        texels_per_m <= 2048.0)) {
    return Fail(message, "texels_per_m must be in [16, 2048]");
  }
  if (!(Finite(tile_size_m) && tile_size_m >= 0.1 && tile_size_m <= 10.0)) {
    return Fail(message, "tile_size_m must be in [0.1, 10]");
  }
  if (!(NonNegative(tile_gain_spread) && tile_gain_spread < 1.0)) {
    return Fail(message, "tile_gain_spread must be in [0, 1)");
  }
  if (!(Finite(mip_bias) && std::abs(mip_bias) <= 4.0)) {
    return Fail(message, "mip_bias must be in [-4, 4]");
  }
  if (!(Finite(view_scale) && view_scale >= 0.25 && view_scale <= 2.0)) {
    return Fail(message, "view_scale must be in [0.25, 2]");
  }
  if (!(NonNegative(exposure_time_s) && exposure_time_s <= 0.1)) {
    return Fail(message, "exposure_time_s must be in [0, 0.1]");
  }
  if (!Positive(blur_step_px)) {
    return Fail(message, "blur_step_px must be > 0");
  }
  if (max_blur_samples < 1 || max_blur_samples > 256) {
    return Fail(message, "max_blur_samples must be in [1, 256]");
  }
  if (!NonNegative(gain_change_per_frame)) {
    return Fail(message, "gain_change_per_frame must be >= 0");
  }
  if (!(Positive(min_gain) && Positive(max_gain) && min_gain <= 1.0 &&
        max_gain >= 1.0)) {
    return Fail(message,
                "min_gain and max_gain must be > 0 with min_gain <= 1 <= "
                "max_gain");
  }
  if (!Positive(cam1_gain_ratio)) {
    return Fail(message, "cam1_gain_ratio must be > 0");
  }
  if (!(Positive(vignetting_corner_gain) && vignetting_corner_gain <= 1.0)) {
    return Fail(message, "vignetting_corner_gain must be in (0, 1]");
  }
  if (!NonNegative(read_noise_grey)) {
    return Fail(message, "read_noise_grey must be >= 0");
  }
  if (!NonNegative(shot_noise_grey)) {
    return Fail(message, "shot_noise_grey must be >= 0");
  }
  SceneLayout layout;  // boxes are checked against the room by the caller
  layout.min_corner = Eigen::Vector3d(-1e9, -1e9, 0.0);
  layout.max_corner = Eigen::Vector3d(1e9, 1e9, 1e9);
  layout.boxes = boxes;
  std::string m;
  if (!layout.Validate(&m)) return Fail(message, m);
  return true;
}

}  // namespace vio
