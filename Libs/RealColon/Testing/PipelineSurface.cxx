#include "PipelineSurface.h"

#include "Cleansing/ElectronicCleansing.h"
#include "Segmentation/LumenSegmentation.h"

#include <algorithm>

namespace colonmap::realcolon::testing {

PipelineSurface SurfaceFromCT(const RealColonPair& pair, phantom::Posture posture, const RealColonOptions& o) {
  NullProgress np;
  const Volume<short> ct = RealColonCT(pair, posture, o, np);
  const cleansing::CleansingResult clean = cleansing::Cleanse(ct, {}, np);
  const segmentation::LumenSegmentation seg = segmentation::SegmentColonLumen(clean.cleansed, {}, np);
  Volume<float> label = seg.label.Like<float>(0.0f);
  std::copy(seg.label.voxels.begin(), seg.label.voxels.end(), label.voxels.begin());
  PipelineSurface out;
  out.surface = surface::ReconstructSurface(label, &clean.cleansed, {}, np);
  out.taggedVoxels = clean.taggedVoxels;
  out.lumenVolumeMl = seg.lumenVolumeMl;
  return out;
}

}  // namespace colonmap::realcolon::testing
