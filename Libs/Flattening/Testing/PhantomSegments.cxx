#include "PhantomSegments.h"

#include "Surface/MeshTopology.h"

#include <cmath>
#include <cstdlib>

namespace colonmap::flattening::testing {

using namespace colonmap::phantom;

PhantomOptions TrueWallOptions(const char* meshStepMm, const char* pointsAround, const char* seed) {
  PhantomOptions o;
  o.meshStepMm = std::atof(meshStepMm);
  o.meshPointsAround = std::atoi(pointsAround);
  o.seed = static_cast<std::uint32_t>(std::atoi(seed));
  return o;
}

TriangleMesh TrueWallWithArcLength(const ScanGeometry& scan, const PhantomOptions& o) {
  TriangleMesh wall = TrueWall(scan, o);
  const Eigen::MatrixXd& s = wall.pointData.at("MaterialS").values;
  wall.pointData["CenterlineArcLength"] = DataArray{(scan.anatomy.length - s.array()).matrix(), false};
  return wall;
}

std::vector<PhantomSegment> PhantomTruthSegments(const ScanGeometry& scan, const PhantomOptions& o) {
  const TriangleMesh wall = TrueWallWithArcLength(scan, o);
  const int nt = std::max(3, o.meshPointsAround);
  const Eigen::MatrixXd& seg = wall.pointData.at("SegmentId").values;
  const Eigen::MatrixXd& ms = wall.pointData.at("MaterialS").values;
  const double twoPi = 2.0 * 3.14159265358979323846;
  std::vector<PhantomSegment> out;
  for (int id = 0; id < 5; ++id) {
    std::vector<bool> keep(wall.F.rows(), false);
    for (Eigen::Index f = 0; f < wall.F.rows(); ++f)
      keep[f] = seg(wall.F(f, 0), 0) == id && seg(wall.F(f, 1), 0) == id && seg(wall.F(f, 2), 0) == id;
    PhantomSegment ps;
    ps.id = id;
    std::vector<int> old;
    surface::KeepFaces(wall.V, wall.F, keep, ps.mesh.V, ps.mesh.F, &old);
    if (ps.mesh.F.rows() == 0) continue;
    for (const auto& [name, array] : wall.pointData) {
      DataArray a{Eigen::MatrixXd(old.size(), array.values.cols()), array.integer};
      for (std::size_t i = 0; i < old.size(); ++i) a.values.row(i) = array.values.row(old[i]);
      ps.mesh.pointData[name] = a;
    }
    // Grid rows of this segment: kept vertices are whole rows, old index = row * nt + column.
    const int row0 = old.front() / nt, row1 = old.back() / nt;
    auto newIndex = [&](int row, int col) { return (row - row0) * nt + ((col % nt) + nt) % nt; };
    for (int k = 0; k < 3; ++k) {
      std::vector<int> column(row1 - row0 + 1);
      for (int i = row0; i <= row1; ++i)
        column[i - row0] = static_cast<int>(std::lround(WrapAngle(scan.anatomy.TaeniaTheta(k, ms(old[(i - row0) * nt], 0))) / twoPi * nt)) % nt;
      column[0] = column[1];  // no step along the first row, which is a boundary loop
      std::vector<int> path;
      int c = column[0];
      for (int i = row0; i <= row1; ++i) {
        path.push_back(newIndex(i, c));
        if (i == row1) break;
        int d = column[i + 1 - row0] - c;
        d = ((d % nt) + nt + nt / 2) % nt - nt / 2;  // wrapped to [-nt/2, nt/2)
        // Row steps (i, c) -> (i, c +- 1), then a vertical edge or the quad's diagonal
        // (i, c) -> (i + 1, c + 1), all edges of the grid triangulation.
        for (; d > 1; --d) path.push_back(newIndex(i, ++c));
        for (; d < 0; ++d) path.push_back(newIndex(i, --c));
        if (d == 1) ++c;
      }
      ps.taenia[k] = Eigen::Map<Eigen::VectorXi>(path.data(), static_cast<Eigen::Index>(path.size()));
    }
    out.push_back(std::move(ps));
  }
  return out;
}

PolylineSet TaeniaePolylines(const std::vector<PhantomSegment>& segments) {
  PolylineSet set;
  std::vector<double> segId, isCut, conf, vid;
  for (const PhantomSegment& s : segments)
    for (int k = 0; k < 3; ++k) {
      Polyline line;
      line.name = TaeniaName(k);
      line.points.resize(s.taenia[k].size(), 3);
      for (Eigen::Index i = 0; i < s.taenia[k].size(); ++i) {
        line.points.row(i) = s.mesh.V.row(s.taenia[k](i));
        vid.push_back(s.taenia[k](i));
      }
      set.lines.push_back(line);
      segId.push_back(s.id);
      isCut.push_back(k == 1 ? 1 : 0);
      conf.push_back(1.0);
    }
  auto column = [](const std::vector<double>& v) {
    return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())).eval();
  };
  set.cellData["SegmentId"] = DataArray{column(segId), true};
  set.cellData["IsCut"] = DataArray{column(isCut), true};
  set.cellData["Confidence"] = DataArray{column(conf), false};
  set.pointData["VertexId"] = DataArray{column(vid), true};
  return set;
}

}  // namespace colonmap::flattening::testing
