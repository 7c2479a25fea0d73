#pragma once
// The ITK side of image I/O, with plain arrays only. ITK 5.2 in Debian bundles its own Eigen
// 3.3, which cannot share a translation unit with the system Eigen 3.4 our Libs use: so code
// that includes ITK headers never includes Eigen, and talks to the rest through this header.
#include <cstddef>
#include <string>
#include <vector>

namespace colonmap::io::detail {

struct ImageGeometry {
  std::size_t size[3] = {0, 0, 0};
  double spacing[3] = {1, 1, 1};
  double origin[3] = {0, 0, 0};
  double direction[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major, columns are the axes
  std::vector<std::string> notes;  // what the user should know about how the file was read
};

// Reads a file (any ITK format) or a folder holding a DICOM series. Throws colonmap::Error: first
// for what CheckImageFile (IO/ImageCheck.h) finds, the same code, then for what the voxels show.
template <typename T>
void ItkReadImage(const std::string& path, const std::string& what, ImageGeometry& geometry,
                  std::vector<T>& voxels);

template <typename T>
void ItkWriteImage(const ImageGeometry& geometry, const T* voxels, const std::string& path,
                   const std::string& what, bool compress);

// Makes ITK's lazily built global state (object factory list, image IO factories, the default
// multi-threader) on the calling thread, so that threads started afterwards only read it.
void ItkPrepareForThreads();

}  // namespace colonmap::io::detail
