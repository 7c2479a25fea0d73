#include "IO/ImageIO.h"

#include "Core/Error.h"
#include "IO/ItkImageBridge.h"

#include <Eigen/LU>

#include <cmath>

namespace colonmap::io {

template <typename T>
Volume<T> ReadImage(const std::string& path, const std::string& what, const NoteSink& note) {
  detail::ImageGeometry g;
  Volume<T> v;
  detail::ItkReadImage<T>(path, what, g, v.voxels);
  for (int d = 0; d < 3; ++d) {
    v.size[d] = g.size[d];
    v.spacing[d] = g.spacing[d];
    v.origin[d] = g.origin[d];
    for (int e = 0; e < 3; ++e) v.direction(d, e) = g.direction[3 * d + e];
  }
  if (v.NumberOfVoxels() == 0) throw InputError(what, path, "image has no voxels");
  if (!v.spacing.allFinite() || (v.spacing.array() <= 0.0).any())
    throw InputError(what, path, "voxel spacing is not a positive finite number");
  if (!v.origin.allFinite() || !v.direction.allFinite() || std::abs(v.direction.determinant()) < 1e-6)
    throw InputError(what, path, "image origin or direction is not valid");
  if (note)
    for (const std::string& n : g.notes) note(n);
  return v;
}

template <typename T>
void WriteImage(const Volume<T>& v, const std::string& path, const std::string& what, Compression compression) {
  if (v.voxels.size() != v.NumberOfVoxels() || v.voxels.empty())
    throw InputError(what, path, "image to write is empty or inconsistent");
  detail::ImageGeometry g;
  for (int d = 0; d < 3; ++d) {
    g.size[d] = v.size[d];
    g.spacing[d] = v.spacing[d];
    g.origin[d] = v.origin[d];
    for (int e = 0; e < 3; ++e) g.direction[3 * d + e] = v.direction(d, e);
  }
  detail::ItkWriteImage<T>(g, v.voxels.data(), path, what, compression == Compression::Fast);
}

template Volume<short> ReadImage<short>(const std::string&, const std::string&, const NoteSink&);
template Volume<unsigned char> ReadImage<unsigned char>(const std::string&, const std::string&, const NoteSink&);
template Volume<float> ReadImage<float>(const std::string&, const std::string&, const NoteSink&);
template void WriteImage<short>(const Volume<short>&, const std::string&, const std::string&, Compression);
template void WriteImage<unsigned char>(const Volume<unsigned char>&, const std::string&, const std::string&, Compression);
template void WriteImage<float>(const Volume<float>&, const std::string&, const std::string&, Compression);

}  // namespace colonmap::io
