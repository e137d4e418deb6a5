#include "navigation/grid.h"

#include <numeric>
#include <stdexcept>
#include <string>

namespace vio {

Grid::Grid(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1 ||
      static_cast<int64_t>(width) * height > (int64_t{1} << 28)) {
    throw std::invalid_argument("Grid: " + std::to_string(width) + " x " +
                                std::to_string(height) +
                                " cells (each side >= 1, at most 2^28 cells)");
  }
  blocked_.assign(static_cast<size_t>(width) * static_cast<size_t>(height), 0);
}

int64_t Grid::CountBlocked() const {
  return std::accumulate(blocked_.begin(), blocked_.end(), int64_t{0});
}

}  // namespace vio
