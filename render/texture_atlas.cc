#include "render/texture_atlas.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>

namespace vio {
namespace {

namespace fs = std::filesystem;

constexpr int kMinCropSide = 16;  // [px]
constexpr int kMinLevelSide = 8;  // [texels]
constexpr int kMaxLevels = 8;

// One tile: the crop resized to `side`, turned, mirrored, brightened.
cv::Mat MakeTile(const cv::Mat& crop, int side, double spread,
                 std::mt19937* rng) {
  cv::Mat tile;
  if (crop.cols == side && crop.rows == side) {
    tile = crop.clone();
  } else {
    cv::resize(crop, tile, cv::Size(side, side), 0, 0, cv::INTER_AREA);
  }
  std::uniform_int_distribution<int> turn(0, 3);
  const int quarter_turns = turn(*rng);
  if (quarter_turns == 1) cv::rotate(tile, tile, cv::ROTATE_90_CLOCKWISE);
  if (quarter_turns == 2) cv::rotate(tile, tile, cv::ROTATE_180);
  if (quarter_turns == 3) {
    cv::rotate(tile, tile, cv::ROTATE_90_COUNTERCLOCKWISE);
  }
  std::bernoulli_distribution mirror(0.5);
  if (mirror(*rng)) cv::flip(tile, tile, 1);
  std::uniform_real_distribution<double> gain(1.0 - spread, 1.0 + spread);
  tile.convertTo(tile, CV_8U, gain(*rng));
  return tile;
}

PlaneTexture MakePlaneTexture(const ScenePlane& plane,
                              const std::vector<cv::Mat>& crops,
                              const RenderOptions& options, std::mt19937* rng) {
  const int side =
      std::max(1, static_cast<int>(
                      std::lround(options.tile_size_m * options.texels_per_m)));
  const int tiles_u =
      static_cast<int>(std::ceil(plane.size_u_m / options.tile_size_m - 1e-9));
  const int tiles_v =
      static_cast<int>(std::ceil(plane.size_v_m / options.tile_size_m - 1e-9));
  cv::Mat level0(tiles_v * side, tiles_u * side, CV_8U);
  std::uniform_int_distribution<size_t> pick(0, crops.size() - 1);
  for (int j = 0; j < tiles_v; ++j) {
    for (int i = 0; i < tiles_u; ++i) {
      const cv::Mat tile =
          MakeTile(crops[pick(*rng)], side, options.tile_gain_spread, rng);
      tile.copyTo(level0(cv::Rect(i * side, j * side, side, side)));
    }
  }
  PlaneTexture texture;
  texture.levels.push_back(level0);
  while (static_cast<int>(texture.levels.size()) < kMaxLevels &&
         std::min(texture.levels.back().cols, texture.levels.back().rows) >=
             2 * kMinLevelSide) {
    cv::Mat next;
    cv::pyrDown(texture.levels.back(), next);
    texture.levels.push_back(next);
  }
  return texture;
}

}  // namespace

std::string BuiltInTextureFolder() { return VIO_RENDER_TEXTURE_DIR; }

std::vector<cv::Mat> LoadTextureCrops(const std::string& folder) {
  std::error_code ec;
  std::vector<std::string> files;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end;
       it.increment(ec)) {
    if (it->path().extension() == ".png") files.push_back(it->path().string());
  }
  if (ec) throw std::runtime_error(folder + ": cannot list the folder");
  if (files.empty()) {
    throw std::runtime_error(folder + ": holds no texture (*.png)");
  }
  std::sort(files.begin(), files.end());
  std::vector<cv::Mat> crops;
  for (const std::string& file : files) {
    cv::Mat crop = cv::imread(file, cv::IMREAD_GRAYSCALE);
    if (crop.empty()) {
      throw std::runtime_error(file + ": cannot be decoded as an image");
    }
    if (crop.cols < kMinCropSide || crop.rows < kMinCropSide) {
      throw std::runtime_error(file + ": a texture must be at least 16 x 16");
    }
    crops.push_back(crop);
  }
  return crops;
}

TexturedScene MakeTexturedScene(const SceneGeometry& geometry,
                                const std::vector<cv::Mat>& crops,
                                const RenderOptions& options, uint32_t seed) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("render options: " + message);
  }
  if (crops.empty()) throw std::invalid_argument("no texture crops");
  TexturedScene scene;
  scene.geometry = geometry;
  scene.texels_per_m = options.texels_per_m;
  std::mt19937 rng(seed);
  for (const ScenePlane& plane : geometry.planes()) {
    scene.textures.push_back(MakePlaneTexture(plane, crops, options, &rng));
  }
  return scene;
}

}  // namespace vio
