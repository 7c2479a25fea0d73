// Test inputs for ColonSurface: a phantom CT without fluid, its exact lumen label map (unsigned
// char 0/1, and a short copy with lumen value 3) and the true wall, at a given spacing.
// Usage: ColonSurfaceMakeTestData <output folder> <spacing mm, or x,y,z> [seed]
#include "IO/ImageIO.h"
#include "IO/MeshIO.h"
#include "Phantom/Phantom.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  using namespace colonmap;
  using namespace colonmap::phantom;
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s <output folder> <spacing mm> [seed]\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path out = argv[1];
    std::filesystem::create_directories(out);
    PhantomOptions o;
    double h[3];
    if (std::sscanf(argv[2], "%lf,%lf,%lf", &h[0], &h[1], &h[2]) == 3) o.spacing = Eigen::Vector3d(h[0], h[1], h[2]);
    else o.spacing = Eigen::Vector3d::Constant(std::atof(argv[2]));
    o.fluid = false;
    if (argc > 3) o.seed = static_cast<std::uint32_t>(std::atoi(argv[3]));
    const ScanGeometry scan = MakeScan(MakeAnatomy(o), Posture::Supine, o);
    NullProgress np;
    const Volume<unsigned char> label = LumenLabel(scan, o, np);
    io::WriteImage(label, (out / "label.nrrd").string(), "label");
    Volume<short> label3;
    label3.size = label.size;
    label3.spacing = label.spacing;
    label3.origin = label.origin;
    label3.direction = label.direction;
    label3.voxels.resize(label.voxels.size());
    for (std::size_t i = 0; i < label.voxels.size(); ++i) label3.voxels[i] = label.voxels[i] ? 3 : 0;
    io::WriteImage(label3, (out / "label3.nrrd").string(), "label 3");
    io::WriteImage(SynthesizeCT(scan, o, np), (out / "ct.nrrd").string(), "CT", io::Compression::None);
    io::WriteMesh(TrueWall(scan, o), (out / "truth.vtp").string(), "true wall");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
