#include "navigation/moving_ai.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "navigation/navigation_error.h"

namespace vio {
namespace {

// Reads a text file line by line (a trailing '\r' removed) and words errors
// as "path:line: message".
class LineReader {
 public:
  explicit LineReader(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw NavigationError(path + ": cannot open the file");
  }
  bool Next(std::string* line) {
    if (!std::getline(in_, *line)) return false;
    ++number_;
    if (!line->empty() && line->back() == '\r') line->pop_back();
    return true;
  }
  int number() const { return number_; }
  [[noreturn]] void Fail(const std::string& message) const {
    throw NavigationError(path_ + ":" + std::to_string(number_) + ": " +
                          message);
  }

 private:
  std::string path_;
  std::ifstream in_;
  int number_ = 0;
};

std::vector<std::string> Words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

bool Blank(const std::string& line) { return Words(line).empty(); }

// The whole word as an int in [lo, hi].
int Integer(const LineReader& r, const std::string& word, const char* what,
            int lo, int hi) {
  size_t used = 0;
  long value = 0;
  try {
    value = std::stol(word, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != word.size()) {
    r.Fail(std::string(what) + " is not an integer ('" + word + "')");
  }
  if (value < lo || value > hi) {
    r.Fail(std::string(what) + " " + word + " is out of range [" +
           std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return static_cast<int>(value);
}

double Real(const LineReader& r, const std::string& word, const char* what) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(word, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != word.size() || !std::isfinite(value)) {
    r.Fail(std::string(what) + " is not a number ('" + word + "')");
  }
  return value;
}

// The next non-blank line; fails with `missing` at the end of the file.
std::string NextContent(LineReader* r, const std::string& missing) {
  std::string line;
  while (r->Next(&line)) {
    if (!Blank(line)) return line;
  }
  r->Fail(missing);
}

constexpr int kMaxSide = 1 << 14;  // [cells]

// "height 12" / "width 7": the value.
int HeaderValue(LineReader* r, const char* key) {
  const std::string line =
      NextContent(r, std::string("the header ends before '") + key + "'");
  const std::vector<std::string> w = Words(line);
  if (w.size() != 2 || w[0] != key) {
    r->Fail(std::string("expected '") + key + " N', got '" + line + "'");
  }
  return Integer(*r, w[1], key, 1, kMaxSide);
}

bool Passable(char c) { return c == '.' || c == 'G' || c == 'S'; }
bool KnownBlocked(char c) {
  return c == '@' || c == 'O' || c == 'T' || c == 'W';
}

std::ofstream OpenForWriting(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw NavigationError(path + ": cannot open the file for writing");
  return out;
}

}  // namespace

Grid ReadMovingAiMap(const std::string& path) {
  LineReader r(path);
  const std::string type = NextContent(&r, "the file is empty");
  if (Words(type) != std::vector<std::string>{"type", "octile"}) {
    r.Fail("expected 'type octile', got '" + type + "'");
  }
  const int height = HeaderValue(&r, "height");
  const int width = HeaderValue(&r, "width");
  const std::string map = NextContent(&r, "the header ends before 'map'");
  if (Words(map) != std::vector<std::string>{"map"}) {
    r.Fail("expected 'map', got '" + map + "'");
  }
  Grid grid(width, height);
  std::string line;
  for (int y = 0; y < height; ++y) {
    if (!r.Next(&line)) {
      r.Fail("the map has " + std::to_string(y) + " rows, the header says " +
             "height " + std::to_string(height));
    }
    if (static_cast<int>(line.size()) != width) {
      r.Fail("row " + std::to_string(y) + " has " +
             std::to_string(line.size()) + " cells, the header says width " +
             std::to_string(width));
    }
    for (int x = 0; x < width; ++x) {
      const char c = line[x];
      if (!Passable(c) && !KnownBlocked(c)) {
        r.Fail("column " + std::to_string(x) + ": unknown terrain '" +
               std::string(1, c) + "' (passable . G S, blocked @ O T W)");
      }
      grid.SetBlocked({x, y}, !Passable(c));
    }
  }
  while (r.Next(&line)) {
    if (!Blank(line)) {
      r.Fail("text after the " + std::to_string(height) + " map rows");
    }
  }
  return grid;
}

std::vector<MovingAiScenario> ReadMovingAiScenarios(const std::string& path) {
  LineReader r(path);
  const std::string version = NextContent(&r, "the file is empty");
  const std::vector<std::string> v = Words(version);
  if (v.size() != 2 || v[0] != "version" || (v[1] != "1" && v[1] != "1.0")) {
    r.Fail("expected 'version 1' or 'version 1.0', got '" + version + "'");
  }
  std::vector<MovingAiScenario> scenarios;
  std::string line;
  while (r.Next(&line)) {
    const std::vector<std::string> w = Words(line);
    if (w.empty()) continue;
    if (w.size() != 9) {
      r.Fail("a scenario has 9 fields, got " + std::to_string(w.size()));
    }
    MovingAiScenario s;
    s.line = r.number();
    s.bucket = Integer(r, w[0], "bucket", 0, 1 << 30);
    s.map = w[1];
    s.map_width = Integer(r, w[2], "map width", 1, kMaxSide);
    s.map_height = Integer(r, w[3], "map height", 1, kMaxSide);
    s.start = {Integer(r, w[4], "start x", -kMaxSide, kMaxSide),
               Integer(r, w[5], "start y", -kMaxSide, kMaxSide)};
    s.goal = {Integer(r, w[6], "goal x", -kMaxSide, kMaxSide),
              Integer(r, w[7], "goal y", -kMaxSide, kMaxSide)};
    s.optimal_length = Real(r, w[8], "optimal length");
    scenarios.push_back(s);
  }
  return scenarios;
}

void CheckScenario(const Grid& grid, const MovingAiScenario& s,
                   const std::string& scen_path) {
  const std::string where = scen_path + ":" + std::to_string(s.line) + ": ";
  if (s.map_width != grid.width() || s.map_height != grid.height()) {
    throw NavigationError(
        where + "the scenario's map is " + std::to_string(s.map_width) + " x " +
        std::to_string(s.map_height) + ", the map file's " +
        std::to_string(grid.width()) + " x " + std::to_string(grid.height()));
  }
  const std::pair<const char*, Cell> ends[] = {{"start", s.start},
                                               {"goal", s.goal}};
  for (const auto& [name, c] : ends) {
    const std::string cell = std::string(name) + " (" + std::to_string(c.x) +
                             ", " + std::to_string(c.y) + ")";
    if (!grid.Contains(c))
      throw NavigationError(where + cell + " is off the map");
    if (grid.Blocked(c)) throw NavigationError(where + cell + " is blocked");
  }
}

void WriteMovingAiMap(const std::string& path, const Grid& grid) {
  std::ofstream out = OpenForWriting(path);
  out << "type octile\nheight " << grid.height() << "\nwidth " << grid.width()
      << "\nmap\n";
  std::string row(grid.width(), '.');
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      row[x] = grid.Blocked({x, y}) ? '@' : '.';
    }
    out << row << '\n';
  }
  if (!out) throw NavigationError(path + ": write failed");
}

void WriteMovingAiScenarios(const std::string& path,
                            const std::vector<MovingAiScenario>& scenarios) {
  std::ofstream out = OpenForWriting(path);
  out << "version 1\n";
  char length[64];
  for (const MovingAiScenario& s : scenarios) {
    std::snprintf(length, sizeof(length), "%.8f", s.optimal_length);
    out << s.bucket << '\t' << s.map << '\t' << s.map_width << '\t'
        << s.map_height << '\t' << s.start.x << '\t' << s.start.y << '\t'
        << s.goal.x << '\t' << s.goal.y << '\t' << length << '\n';
  }
  if (!out) throw NavigationError(path + ": write failed");
}

}  // namespace vio
