// The CT -> surface accuracy on cached pairs (scripts/registration_seeds.py caches: phantom/ with
// {scan}_truth.vtp, surface/{scan}_surface.vtp): distance of each reconstructed vertex to the true
// wall, over the vertices whose nearest true point is 3 mm or more from the wall's open end loops
// (the reconstruction is closed there). One JSON line per scan, with where the largest distance
// is (material s of the nearest true point, its segment, and how many vertices lie over 1 mm),
// and the symmetric figures (both directions pooled: also each true-wall vertex 3 mm or more from
// the end loops to the reconstruction), as the phantom's surface test measures them.
//
//   RealColonSurfaceAccuracy CACHE/seed1 [CACHE/seed2 ...]
#include "IO/MeshIO.h"
#include "Surface/MeshTopology.h"
#include "Surface/SurfaceDistance.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

using namespace colonmap;

int main(int argc, char** argv) {
  try {
    for (int a = 1; a < argc; ++a)
      for (const std::string scan : {"supine", "prone"}) {
        const std::string dir = argv[a];
        const TriangleMesh truth = io::ReadMesh(dir + "/phantom/" + scan + "_truth.vtp", "true wall");
        const TriangleMesh recon = io::ReadMesh(dir + "/surface/" + scan + "_surface.vtp", "surface");
        const surface::ClosestPoints cp = surface::ClosestOnSurface(truth.V, truth.F, recon.V);
        Eigen::MatrixXd ends(0, 3);
        for (const auto& loop : surface::BoundaryLoops(truth.F)) {
          ends.conservativeResize(ends.rows() + static_cast<Eigen::Index>(loop.size()), 3);
          for (std::size_t i = 0; i < loop.size(); ++i) ends.row(ends.rows() - static_cast<Eigen::Index>(loop.size() - i)) = truth.V.row(loop[i]);
        }
        std::vector<double> d;
        Eigen::Index worst = -1;
        long overOneMm = 0;
        for (Eigen::Index i = 0; i < recon.V.rows(); ++i)
          if ((ends.rowwise() - cp.point.row(i)).rowwise().norm().minCoeff() > 3.0) {
            d.push_back(cp.distance(i));
            if (worst < 0 || cp.distance(i) > cp.distance(worst)) worst = i;
            overOneMm += cp.distance(i) > 1.0;
          }
        double worstS = 0.0;
        int worstSegment = -1;
        if (worst >= 0 && truth.pointData.count("MaterialS") && truth.pointData.count("SegmentId")) {
          const Eigen::Vector3i f = truth.F.row(cp.cell[static_cast<std::size_t>(worst)]);
          worstS = truth.pointData.at("MaterialS").values(f(0), 0);
          worstSegment = static_cast<int>(truth.pointData.at("SegmentId").values(f(0), 0));
        }
        std::vector<double> both = d;
        const surface::ClosestPoints back = surface::ClosestOnSurface(recon.V, recon.F, truth.V);
        for (Eigen::Index i = 0; i < truth.V.rows(); ++i)
          if ((ends.rowwise() - truth.V.row(i)).rowwise().norm().minCoeff() > 3.0) both.push_back(back.distance(i));
        const auto stats = [](std::vector<double>& x) {
          std::sort(x.begin(), x.end());
          double mean = 0.0;
          for (double v : x) mean += v;
          mean /= static_cast<double>(std::max<std::size_t>(1, x.size()));
          return std::make_pair(mean, x.empty() ? 0.0 : x[static_cast<std::size_t>(0.95 * static_cast<double>(x.size()))]);
        };
        const auto [mean, p95] = stats(d);
        const auto [symmetricMean, symmetricP95] = stats(both);
        const nlohmann::json j = {{"pair", dir}, {"scan", scan}, {"vertices", d.size()}, {"meanMm", mean},
                                  {"p95Mm", p95}, {"symmetricMeanMm", symmetricMean}, {"symmetricP95Mm", symmetricP95},
                                  {"maxMm", d.empty() ? 0.0 : d.back()}, {"verticesOver1Mm", overOneMm},
                                  {"maxAtMaterialS", worstS}, {"maxAtSegment", worstSegment}};
        std::printf("%s\n", j.dump().c_str());
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "RealColonSurfaceAccuracy: %s\n", e.what());
    return 1;
  }
  return 0;
}
