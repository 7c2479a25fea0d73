#pragma once
// An image input checked at the door, without reading its voxels (issue 24): a pipeline that reads
// its second scan only after a minute of work on the first checks both before its first stage.
// No ITK and no Eigen here: any code may include it.
#include <string>

namespace colonmap::io {

// Throws colonmap::Error ("<what> '<path>': <problem>", the words ReadImage uses for the same
// problem: the checks are the ones it runs before it reads the voxels) for a missing file, an
// unknown format, a header ITK cannot read, a header check of IO/NrrdCheck.h, IO/NiftiCheck.h or
// IO/MetaImageCheck.h, a DICOM folder failing IO/DicomCheck.h or holding no series, an image
// with more than three axes, no voxels, a non-finite or non-positive spacing or an invalid
// direction. What only the voxel read finds still waits for ReadImage: NRRD voxel data cut short
// or corrupt, a DICOM series with uneven slice spacing. Host paths ("slicer:0x..") pass unchecked.
void CheckImageFile(const std::string& path, const std::string& what);

}  // namespace colonmap::io
