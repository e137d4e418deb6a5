#include "dataset/landmarks_io.h"

#include <cmath>
#include <fstream>
#include <iomanip>

#include "dataset/csv.h"

namespace vio {

void WriteLandmarksCsv(const std::string& path,
                       const std::vector<LandmarkRow>& landmarks) {
  std::ofstream out(path);
  if (!out) throw DatasetError(path + ": cannot open the file for writing");
  out << std::setprecision(9) << "#x [m],y [m],z [m],parallax [deg]\n";
  for (const LandmarkRow& l : landmarks) {
    out << l.p_w.x() << ',' << l.p_w.y() << ',' << l.p_w.z() << ','
        << std::setprecision(4) << l.parallax_deg << std::setprecision(9)
        << '\n';
  }
  if (!out) throw DatasetError(path + ": write failed");
}

std::vector<LandmarkRow> ReadLandmarksCsv(const std::string& path) {
  CsvReader csv(path);
  std::vector<LandmarkRow> out;
  while (csv.Next()) {
    if (csv.size() != 3 && csv.size() != 4) {
      csv.Fail("a landmark line has 4 fields (x,y,z,parallax_deg) or 3, got " +
               std::to_string(csv.size()));
    }
    LandmarkRow l;
    l.p_w = {csv.Double(0), csv.Double(1), csv.Double(2)};
    if (csv.size() == 4) {
      l.parallax_deg = csv.Double(3);
      if (l.parallax_deg < 0.0) csv.Fail("the parallax is negative");
    }
    out.push_back(l);
  }
  return out;
}

}  // namespace vio
