// A Moving AI scenario file, .scen (navigation/moving_ai.h:
// ReadMovingAiScenarios), each scenario then checked against a 5 x 3 free
// grid (CheckScenario), as vio_plan does with its map. Any refusal is a
// NavigationError naming the file.

#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_input.h"
#include "navigation/moving_ai.h"
#include "navigation/navigation_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vio::fuzz::ScratchFile file("grid.map.scen");
  static const vio::Grid grid(5, 3);
  const std::string& path = file.Write(data, size);
  try {
    for (const vio::MovingAiScenario& s : vio::ReadMovingAiScenarios(path)) {
      vio::fuzz::Require(s.line >= 2, "a scenario before the version line");
      try {
        vio::CheckScenario(grid, s, path);
      } catch (const vio::NavigationError& e) {
        vio::fuzz::RequireNamesFile(e.what(), path);
      }
    }
  } catch (const vio::NavigationError& e) {
    vio::fuzz::RequireNamesFile(e.what(), path);
  }
  return 0;
}
