// The CT -> surface accuracy on cached pairs (scripts/registration_seeds.py caches: phantom/ with
// {scan}_truth.vtp, surface/{scan}_surface.vtp): distance of each reconstructed vertex to the true
// wall, over the vertices whose nearest true point is 3 mm or more from the wall's open end loops
// (the reconstruction is closed there). One JSON line per scan.
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
        for (Eigen::Index i = 0; i < recon.V.rows(); ++i)
          if ((ends.rowwise() - cp.point.row(i)).rowwise().norm().minCoeff() > 3.0) d.push_back(cp.distance(i));
        std::sort(d.begin(), d.end());
        double mean = 0.0;
        for (double x : d) mean += x;
        mean /= std::max<std::size_t>(1, d.size());
        const nlohmann::json j = {{"pair", dir}, {"scan", scan}, {"vertices", d.size()}, {"meanMm", mean},
                                  {"p95Mm", d.empty() ? 0.0 : d[static_cast<std::size_t>(0.95 * d.size())]},
                                  {"maxMm", d.empty() ? 0.0 : d.back()}};
        std::printf("%s\n", j.dump().c_str());
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "RealColonSurfaceAccuracy: %s\n", e.what());
    return 1;
  }
  return 0;
}
