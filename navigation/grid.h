#ifndef VIO_NAVIGATION_GRID_H_
#define VIO_NAVIGATION_GRID_H_

// A 2-D grid of free and blocked cells, indexed as Moving AI maps are:
// x is the column (0 at the left), y the row (0 at the top).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vio {

struct Cell {
  int x = 0;  // column
  int y = 0;  // row
  bool operator==(const Cell& o) const { return x == o.x && y == o.y; }
  bool operator!=(const Cell& o) const { return !(*this == o); }
};

class Grid {
 public:
  Grid() = default;
  // width x height cells, all free. Throws std::invalid_argument unless both
  // are >= 1 and the grid has at most 2^28 cells.
  Grid(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  bool Contains(Cell c) const {
    return c.x >= 0 && c.y >= 0 && c.x < width_ && c.y < height_;
  }
  // Requires Contains(c).
  bool Blocked(Cell c) const { return blocked_[Index(c)] != 0; }
  bool Free(Cell c) const { return Contains(c) && !Blocked(c); }
  void SetBlocked(Cell c, bool blocked) { blocked_[Index(c)] = blocked; }
  int64_t CountBlocked() const;

 private:
  size_t Index(Cell c) const {
    return static_cast<size_t>(c.y) * static_cast<size_t>(width_) +
           static_cast<size_t>(c.x);
  }

  int width_ = 0;
  int height_ = 0;
  std::vector<uint8_t> blocked_;
};

}  // namespace vio

#endif  // VIO_NAVIGATION_GRID_H_
