// A Moving AI grid map, .map (navigation/moving_ai.h: ReadMovingAiMap). A
// map that reads has a positive size whose every cell answers; any refusal
// is a NavigationError naming the file.

#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_input.h"
#include "navigation/moving_ai.h"
#include "navigation/navigation_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("grid.map");
  const std::string& path = file.Write(data, size);
  try {
    const vio::Grid grid = vio::ReadMovingAiMap(path);
    vio::fuzz::Require(grid.width() > 0 && grid.height() > 0, "an empty map");
    int64_t blocked = 0;
    for (int y = 0; y < grid.height(); ++y) {
      for (int x = 0; x < grid.width(); ++x) blocked += grid.Blocked({x, y});
    }
    vio::fuzz::Require(blocked == grid.CountBlocked(),
                       "blocked cells miscounted");
  } catch (const vio::NavigationError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  return 0;
}
