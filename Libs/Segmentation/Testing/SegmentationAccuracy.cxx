// Usage: ColonMapSegmentationAccuracy label.nrrd seed sx,sy,sz fluid(0|1) [supine|prone]
// Prints Dice, volume error and the topology (components, Euler characteristic) of a
// ColonSegmentation output against the phantom's LumenLabel for the same options.
#include "IO/ImageIO.h"
#include "Phantom/Phantom.h"
#include "Segmentation/EulerCharacteristic.h"
#include "SegmentationTestUtils.h"

#include <cstdio>
#include <cstdlib>
#include <string>

using namespace colonmap;

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s label.nrrd seed sx,sy,sz fluid [supine|prone]\n", argv[0]);
    return 2;
  }
  try {
    const Volume<unsigned char> ours = io::ReadImage<unsigned char>(argv[1], "label map");
    phantom::PhantomOptions o;
    o.seed = static_cast<std::uint32_t>(std::atoi(argv[2]));
    double s[3];
    if (std::sscanf(argv[3], "%lf,%lf,%lf", &s[0], &s[1], &s[2]) != 3) return 2;
    o.spacing = Eigen::Vector3d(s[0], s[1], s[2]);
    o.fluid = std::atoi(argv[4]) != 0;
    const bool prone = argc > 5 && std::string(argv[5]) == "prone";
    NullProgress none;
    const phantom::ScanGeometry scan =
        phantom::MakeScan(phantom::MakeAnatomy(o), prone ? phantom::Posture::Prone : phantom::Posture::Supine, o);
    const Volume<unsigned char> truth = phantom::LumenLabel(scan, o, none);
    if (truth.size != ours.size) {
      std::fprintf(stderr, "grid mismatch\n");
      return 1;
    }
    std::size_t a = 0, b = 0, both = 0;
    for (std::size_t v = 0; v < ours.voxels.size(); ++v) {
      a += ours.voxels[v] != 0;
      b += truth.voxels[v] != 0;
      both += ours.voxels[v] && truth.voxels[v];
    }
    const double ml = o.spacing.prod() / 1000.0;
    std::printf("Dice %.5f, ours %.1f ml, truth %.1f ml, volume error %+.3f %%, ours outside truth %.3f %%, "
                "truth missed %.3f %%\n",
                2.0 * double(both) / double(a + b), double(a) * ml, double(b) * ml,
                100.0 * (double(a) - double(b)) / double(b), 100.0 * double(a - both) / double(a),
                100.0 * double(b - both) / double(b));
    std::printf("components %d, background components %d, Euler characteristic %lld\n",
                segmentation::testing::Components(ours, 1), segmentation::testing::Components(ours, 0),
                static_cast<long long>(segmentation::EulerCharacteristic(ours)));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
