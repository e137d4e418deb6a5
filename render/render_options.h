#ifndef VIO_RENDER_RENDER_OPTIONS_H_
#define VIO_RENDER_RENDER_OPTIONS_H_

// Options of the image renderer (render/sequence_renderer.h), without OpenCV
// so that config/ can fill them. Every field has a default with its unit;
// Validate() writes a message that starts with the field's YAML name (the
// render: block of a simulator preset, config/render_config.h).

#include <string>
#include <vector>

#include "render/scene.h"

namespace vio {

// Boxes standing on the floor of the simulator's 14 x 12 x 4 m room, clear
// of the default and aggressive presets' ellipses (3 x 2 m around the
// centre): one in the middle, three between the path and the walls.
std::vector<SceneBox> DefaultSceneBoxes();

struct RenderOptions {
  // Folder of the texture crops (*.png, 8-bit grey). Empty: the crops of
  // real EuRoC images shipped in render/textures.
  std::string texture_folder;
  double texels_per_m = 256.0;    // texture resolution on every face [1/m]
  double tile_size_m = 1.0;       // each face is tiled with crops this big [m]
  double tile_gain_spread = 0.2;  // tile brightness x U(1 - s, 1 + s) [-]
  // Mip level = log2(texels per pixel) + mip_bias, rounded: > 0 blurs
  // more, < 0 aliases more [-].
  double mip_bias = 0.0;
  // Focal length of the intermediate undistorted view relative to the
  // camera's: 1 keeps the image centre as sharp as the camera resolves
  // it; 0.75 renders about twice as fast with a softer centre [-].
  double view_scale = 1.0;
  std::vector<SceneBox> boxes = DefaultSceneBoxes();

  // Motion blur: the shutter is open exposure_time_s around the frame's
  // exposure time; the image is the mean of renders spaced so that the
  // image moves at most blur_step_px between two of them (at most
  // max_blur_samples). 0 s: no blur.
  double exposure_time_s = 0.004;  // [s]
  double blur_step_px = 1.0;       // [px]
  int max_blur_samples = 16;       // [-]

  // Brightness = radiance x gain x vignetting. The gain follows a random
  // walk of log(gain) with this std per frame, reflected into
  // [min_gain, max_gain] (auto-exposure); cam1 has cam1_gain_ratio times
  // cam0's gain (the two EuRoC cameras expose differently).
  double gain_change_per_frame = 0.02;  // std of the log-gain step [-]
  double min_gain = 0.7;                // [-]
  double max_gain = 1.3;                // [-]
  double cam1_gain_ratio = 0.9;         // [-]
  // Vignetting: gain 1 at the principal point falling quadratically with
  // the pixel radius to this value at the farthest image corner [-].
  double vignetting_corner_gain = 0.7;
  // Sensor noise, Gaussian per pixel with variance
  //   read_noise_grey^2 + shot_noise_grey * I   (I the noise-free grey)
  double read_noise_grey = 1.5;   // std [grey levels]
  double shot_noise_grey = 0.02;  // variance per grey level [grey levels]

  // True when every field is in range; else false with a message that
  // starts with the offending field's name.
  bool Validate(std::string* message) const;
};

}  // namespace vio

#endif  // VIO_RENDER_RENDER_OPTIONS_H_
