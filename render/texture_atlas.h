#ifndef VIO_RENDER_TEXTURE_ATLAS_H_
#define VIO_RENDER_TEXTURE_ATLAS_H_

// The textures of the scene's planes, tiled from crops of real photographs.
//
// A plane's texture holds texels_per_m texels per metre along its axes:
// texel (s, t) (OpenCV's convention, centre of the first texel at (0, 0);
// s along axis_u, t along axis_v) shows the plane point
//   (a, b) = ((s + 0.5) / texels_per_m, (t + 0.5) / texels_per_m)   [m].
// The texture is a grid of tiles of tile_size_m, each a crop (resized to the
// tile when needed), turned by a multiple of 90 degrees, maybe mirrored and
// scaled in brightness by U(1 - tile_gain_spread, 1 + tile_gain_spread), all
// drawn from the seed. Level l of the mip pyramid is cv::pyrDown of level
// l - 1 (a Gaussian prefilter, then every second texel), so level-l texel
// s_l sits at level-0 texel s = 2^l s_l.

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "render/render_options.h"
#include "render/scene.h"

namespace vio {

// Every *.png of `folder`, in name order, decoded as 8-bit grey. Throws
// std::runtime_error naming the folder when it holds none, and naming the
// file when one cannot be decoded or is smaller than 16 x 16.
std::vector<cv::Mat> LoadTextureCrops(const std::string& folder);

// render/textures in the source tree (the crops of real EuRoC images).
std::string BuiltInTextureFolder();

struct PlaneTexture {
  std::vector<cv::Mat> levels;  // 8-bit grey; levels[0] at texels_per_m
};

// The scene's geometry and one texture per plane.
struct TexturedScene {
  SceneGeometry geometry;
  std::vector<PlaneTexture> textures;  // textures[i] for geometry.planes()[i]
  double texels_per_m = 256.0;
};

// Tiles every plane of `geometry` from `crops` as described above. Levels
// are made down to a side of 8 texels or 8 levels. Throws
// std::invalid_argument when `crops` is empty or the options are invalid.
TexturedScene MakeTexturedScene(const SceneGeometry& geometry,
                                const std::vector<cv::Mat>& crops,
                                const RenderOptions& options, uint32_t seed);

}  // namespace vio

#endif  // VIO_RENDER_TEXTURE_ATLAS_H_
