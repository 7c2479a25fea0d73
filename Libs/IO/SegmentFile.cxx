#include "IO/SegmentFile.h"

#include "Core/Error.h"

namespace colonmap::io {

void CheckSegmentId(const TriangleMesh& mesh, int id, const std::string& what, const std::string& path) {
  static const char* names[5] = {"A", "T", "D", "S", "R"};
  const auto sid = mesh.pointData.find("SegmentId");
  if (sid == mesh.pointData.end()) return;
  for (Eigen::Index k = 0; k < sid->second.values.size(); ++k) {
    const double v = sid->second.values(k);
    if (v == id || !(v >= 0 && v < 5)) continue;
    const int other = static_cast<int>(v);
    throw InputError(what, path, std::string("holds segment ") + names[other] + " (SegmentId " + std::to_string(other) +
                                     "), not " + names[id]);
  }
}

}  // namespace colonmap::io
