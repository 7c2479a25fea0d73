// Test input: a real colon's lumen mask with its handles, as another tool would deliver it:
// the Gut Cell Atlas colon (welded pieces, Analysis/GcaModel.h) voxelised on a grid. Prints the
// mask's 26-connected components and handles (from its Euler characteristic, cavities filled).
//   ColonSurfaceMakeAtlasMask <GCA model folder> <out.nii.gz> <spacing mm>
#include "Analysis/GcaModel.h"
#include "IO/ImageIO.h"
#include "Segmentation/LumenTopology.h"

#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char** argv) {
  using namespace colonmap;
  if (argc != 4) {
    std::fprintf(stderr, "usage: ColonSurfaceMakeAtlasMask <GCA model folder> <out.nii.gz> <spacing mm>\n");
    return 2;
  }
  try {
    const analysis::GcaModel g = analysis::ReadGcaModel(argv[1]);
    const Volume<unsigned char> mask = analysis::VoxeliseSurface(analysis::WeldGcaColon(g).colon, std::atof(argv[3]));
    NullProgress np;
    const segmentation::LumenTopology t = segmentation::SimplifyLumenTopology(mask, 2, np);
    io::WriteImage(mask, argv[2], "mask", io::Compression::Fast);
    std::printf("components %d handles %ld\n", t.components, t.handles);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ColonSurfaceMakeAtlasMask: %s\n", e.what());
    return 1;
  }
  return 0;
}
