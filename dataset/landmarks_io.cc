#include "dataset/landmarks_io.h"

#include <cmath>
#include <iomanip>

#include "dataset/csv.h"

namespace vio {

void WriteLandmarksCsv(const std::string& path,
                       const std::vector<LandmarkRow>& landmarks) {
  LandmarksCsvWriter writer(path);
  for (const LandmarkRow& l : landmarks) writer.Write(l);
  writer.Close();
}

LandmarksCsvWriter::LandmarksCsvWriter(const std::string& path)
    : path_(path), out_(path) {
  if (!out_) throw DatasetError(path + ": cannot open the file for writing");
  out_ << std::setprecision(9) << "#x [m],y [m],z [m],parallax [deg]\n";
}

void LandmarksCsvWriter::Write(const LandmarkRow& l) {
  out_ << l.p_w.x() << ',' << l.p_w.y() << ',' << l.p_w.z() << ','
       << std::setprecision(4) << l.parallax_deg << std::setprecision(9)
       << '\n';
  if (!out_) throw DatasetError(path_ + ": write failed");
  ++rows_;
}

void LandmarksCsvWriter::Close() {
  out_.close();
  if (!out_) throw DatasetError(path_ + ": write failed");
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
