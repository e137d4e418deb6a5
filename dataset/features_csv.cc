#include "dataset/features_csv.h"

#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <unordered_set>

#include "dataset/csv.h"

namespace vio {

std::vector<FeatureFrame> ReadFeaturesCsv(const std::string& path, int camera) {
  CsvReader csv(path);
  std::vector<FeatureFrame> frames;
  std::unordered_set<int64_t> ids_in_frame;
  while (csv.Next()) {
    csv.ExpectAtLeast(4);
    if (csv.size() != 4) {
      csv.Fail("expected 4 fields (timestamp, feature_id, u, v), got " +
               std::to_string(csv.size()));
    }
    const int64_t t_ns = csv.Int64(0);
    FeatureObservation obs;
    obs.feature_id = csv.Int64(1);
    obs.camera = camera;
    obs.uv = {csv.Double(2), csv.Double(3)};
    if (obs.feature_id < 0) {
      csv.Fail("feature_id must be >= 0 (got " +
               std::to_string(obs.feature_id) + ")");
    }
    if (frames.empty() || t_ns > frames.back().t_ns) {
      frames.push_back(FeatureFrame{t_ns, {}});
      ids_in_frame.clear();
    } else if (t_ns < frames.back().t_ns) {
      csv.Fail("timestamp " + std::to_string(t_ns) +
               " is before the previous one (" +
               std::to_string(frames.back().t_ns) + ")");
    }
    if (!ids_in_frame.insert(obs.feature_id).second) {
      csv.Fail("feature_id " + std::to_string(obs.feature_id) +
               " appears twice at timestamp " + std::to_string(t_ns));
    }
    frames.back().observations.push_back(obs);
  }
  return frames;
}

void WriteFeaturesCsv(const std::string& path,
                      const std::vector<FeatureFrame>& frames, int camera) {
  std::ofstream out(path);
  if (!out) throw DatasetError(path + ": cannot open the file for writing");
  out << "#timestamp [ns],feature_id,u [px],v [px]\n";
  char line[128];
  for (const FeatureFrame& frame : frames) {
    for (const FeatureObservation& obs : frame.observations) {
      if (obs.camera != camera) continue;
      std::snprintf(line, sizeof(line), "%" PRId64 ",%" PRId64 ",%.6f,%.6f\n",
                    frame.t_ns, obs.feature_id, obs.uv.x(), obs.uv.y());
      out << line;
    }
  }
  if (!out) throw DatasetError(path + ": write failed");
}

}  // namespace vio
