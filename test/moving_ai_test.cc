// Moving AI map and scenario files: hand-made files in the published format
// (terrain letters, tabs, CRLF, "version 1.0"), every kind of malformed line
// as a file:line error, and a round trip through the writers.

#include "navigation/moving_ai.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "navigation/astar.h"
#include "navigation/grid_generator.h"
#include "navigation/navigation_error.h"
#include "testing/expect_error.h"
#include "testing/temp_folder.h"

namespace vio {
namespace {

using testing::TempFolder;

constexpr char kMap[] =
    "type octile\n"
    "height 3\n"
    "width 5\n"
    "map\n"
    ".GS@O\n"
    "TW...\n"
    ".....\n";

TEST(MovingAi, ReadsTheTerrainLetters) {
  TempFolder dir;
  dir.Write("a.map", kMap);
  const Grid grid = ReadMovingAiMap(dir.Path("a.map"));
  ASSERT_EQ(grid.width(), 5);
  ASSERT_EQ(grid.height(), 3);
  const char* expected[] = {"...##", "##...", "....."};
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      EXPECT_EQ(grid.Blocked({x, y}), expected[y][x] == '#')
          << "cell " << x << "," << y;
    }
  }
}

TEST(MovingAi, ReadsScenariosWithTabsAndCrlf) {
  TempFolder dir;
  dir.Write("a.map.scen",
            "version 1.0\r\n"
            "0\tmaps/a.map\t5\t3\t0\t0\t4\t2\t4.82842712\r\n"
            "\r\n"
            "3\tmaps/a.map\t5\t3\t2\t1\t2\t1\t0\r\n");
  const std::vector<MovingAiScenario> s =
      ReadMovingAiScenarios(dir.Path("a.map.scen"));
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].line, 2);
  EXPECT_EQ(s[0].map, "maps/a.map");
  EXPECT_EQ(s[0].map_width, 5);
  EXPECT_EQ(s[0].map_height, 3);
  EXPECT_EQ(s[0].start, (Cell{0, 0}));
  EXPECT_EQ(s[0].goal, (Cell{4, 2}));
  EXPECT_DOUBLE_EQ(s[0].optimal_length, 4.82842712);
  EXPECT_EQ(s[1].line, 4);
  EXPECT_EQ(s[1].bucket, 3);
}

std::string MapError(const std::string& text) {
  TempFolder dir;
  dir.Write("bad.map", text);
  return ErrorMessage<NavigationError>(
      [&] { ReadMovingAiMap(dir.Path("bad.map")); });
}

TEST(MovingAi, MalformedMapsNameFileAndLine) {
  using ::testing::HasSubstr;
  EXPECT_THAT(MapError("type hex\nheight 1\nwidth 1\nmap\n.\n"),
              HasSubstr("bad.map:1: expected 'type octile'"));
  EXPECT_THAT(MapError("type octile\nwidth 1\nheight 1\nmap\n.\n"),
              HasSubstr("bad.map:2: expected 'height N'"));
  EXPECT_THAT(MapError("type octile\nheight x\nwidth 1\nmap\n.\n"),
              HasSubstr("bad.map:2: height is not an integer ('x')"));
  EXPECT_THAT(MapError("type octile\nheight 0\nwidth 1\nmap\n.\n"),
              HasSubstr("bad.map:2: height 0 is out of range"));
  EXPECT_THAT(
      MapError("type octile\nheight 2\nwidth 3\nmap\n...\n..\n"),
      HasSubstr("bad.map:6: row 1 has 2 cells, the header says width 3"));
  EXPECT_THAT(MapError("type octile\nheight 2\nwidth 3\nmap\n...\n.x.\n"),
              HasSubstr("bad.map:6: column 1: unknown terrain 'x'"));
  EXPECT_THAT(
      MapError("type octile\nheight 3\nwidth 1\nmap\n.\n.\n"),
      HasSubstr("bad.map:6: the map has 2 rows, the header says height 3"));
  EXPECT_THAT(MapError("type octile\nheight 1\nwidth 1\nmap\n.\n.\n"),
              HasSubstr("bad.map:6: text after the 1 map rows"));
  EXPECT_THAT(MapError(""), HasSubstr("bad.map:0: the file is empty"));
  EXPECT_THAT(ErrorMessage<NavigationError>(
                  [] { ReadMovingAiMap("/no/such/file.map"); }),
              HasSubstr("/no/such/file.map: cannot open the file"));
}

std::string ScenError(const std::string& text) {
  TempFolder dir;
  dir.Write("bad.scen", text);
  return ErrorMessage<NavigationError>(
      [&] { ReadMovingAiScenarios(dir.Path("bad.scen")); });
}

TEST(MovingAi, MalformedScenariosNameFileAndLine) {
  using ::testing::HasSubstr;
  EXPECT_THAT(ScenError("version 2\n"),
              HasSubstr("bad.scen:1: expected 'version 1' or 'version 1.0'"));
  EXPECT_THAT(ScenError("version 1\n0 a.map 5 3 0 0 4 2\n"),
              HasSubstr("bad.scen:2: a scenario has 9 fields, got 8"));
  EXPECT_THAT(ScenError("version 1\n0 a.map 5 3 0 0 4 2.5 1\n"),
              HasSubstr("bad.scen:2: goal y is not an integer ('2.5')"));
  EXPECT_THAT(ScenError("version 1\n\n0 a.map 5 3 0 0 4 2 nan\n"),
              HasSubstr("bad.scen:3: optimal length is not a number ('nan')"));
}

TEST(MovingAi, ScenariosOffTheMapOrBlockedNameFileAndLine) {
  using ::testing::HasSubstr;
  TempFolder dir;
  dir.Write("a.map", kMap);
  dir.Write("a.scen",
            "version 1\n"
            "0 a.map 5 3 0 0 4 2 1\n"
            "0 a.map 5 3 0 0 5 2 1\n"
            "0 a.map 5 3 3 0 4 2 1\n"
            "0 a.map 6 3 0 0 4 2 1\n");
  const Grid grid = ReadMovingAiMap(dir.Path("a.map"));
  const auto s = ReadMovingAiScenarios(dir.Path("a.scen"));
  const std::string path = dir.Path("a.scen");
  CheckScenario(grid, s[0], path);
  EXPECT_THAT(
      ErrorMessage<NavigationError>([&] { CheckScenario(grid, s[1], path); }),
      HasSubstr("a.scen:3: goal (5, 2) is off the map"));
  EXPECT_THAT(
      ErrorMessage<NavigationError>([&] { CheckScenario(grid, s[2], path); }),
      HasSubstr("a.scen:4: start (3, 0) is blocked"));
  EXPECT_THAT(
      ErrorMessage<NavigationError>([&] { CheckScenario(grid, s[3], path); }),
      HasSubstr("a.scen:5: the scenario's map is 6 x 3, the map "
                "file's 5 x 3"));
}

// A generated maze and its scenarios written, read back and solved: the
// lengths survive the 8 decimals of the file.
TEST(MovingAi, WrittenFilesReadBackAndSolveToTheirLengths) {
  TempFolder dir;
  const Grid maze = MazeGrid(41, 31, 5);
  WriteMovingAiMap(dir.Path("maze.map"), maze);
  const Grid read = ReadMovingAiMap(dir.Path("maze.map"));
  ASSERT_EQ(read.width(), maze.width());
  ASSERT_EQ(read.height(), maze.height());
  for (int y = 0; y < maze.height(); ++y) {
    for (int x = 0; x < maze.width(); ++x) {
      ASSERT_EQ(read.Blocked({x, y}), maze.Blocked({x, y}));
    }
  }
  GridPlanner planner(maze);
  std::vector<MovingAiScenario> scenarios;
  for (const auto& [s, g] : RandomQueries(maze, 20, 9)) {
    MovingAiScenario sc;
    sc.map = "maze.map";
    sc.map_width = maze.width();
    sc.map_height = maze.height();
    sc.start = s;
    sc.goal = g;
    sc.optimal_length = planner.Plan(s, g).length;
    scenarios.push_back(sc);
  }
  WriteMovingAiScenarios(dir.Path("maze.map.scen"), scenarios);
  const auto back = ReadMovingAiScenarios(dir.Path("maze.map.scen"));
  ASSERT_EQ(back.size(), scenarios.size());
  for (size_t i = 0; i < back.size(); ++i) {
    CheckScenario(read, back[i], "maze.map.scen");
    EXPECT_NEAR(GridPlanner(read).Plan(back[i].start, back[i].goal).length,
                back[i].optimal_length, 5e-9);
    EXPECT_EQ(back[i].line, static_cast<int>(i) + 2);
  }
}

}  // namespace
}  // namespace vio
