#pragma once
// Area-uniform sample points on a triangle mesh, so that statistics over wall points do not
// depend on how finely (or how unevenly) a surface was meshed: a real, decimated CT surface
// (edges of ~3 mm) and the phantom's regular grid (~1 mm) are measured alike.
//
//   Eigen::MatrixXd P = SampleSurface(V, F, 1.0);   // ~ one point per 1 mm^2 of surface
//
// Deterministic: a fixed-seed std::mt19937_64 (its output sequence is fixed by the C++
// standard; the conversion to [0, 1) is done here, not by a std distribution), so the same
// mesh gives the same points on every platform. Eigen and std only.
#include <Eigen/Core>
#include <cstdint>

namespace colonmap {
namespace analysis {

// V: n x 3 vertices, F: m x 3 triangles. Each triangle of area A gets floor(A / areaPerSample
// + u) points (u uniform in [0, 1)), uniformly distributed over it; in expectation one point
// per areaPerSample of surface. Degenerate triangles get none. Returns k x 3 points.
Eigen::MatrixXd SampleSurface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double areaPerSample,
                              std::uint64_t seed = 1);

}  // namespace analysis
}  // namespace colonmap
