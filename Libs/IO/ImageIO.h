#pragma once
// Image files <-> Volume, through itk::ImageFileReader/Writer only (so that in-process Slicer
// paths such as "slicer:0x..#vtkMRMLScalarVolumeNode1" work through Slicer's own ImageIO).
// Formats: NRRD (default), NIfTI, MetaImage, and a folder holding a DICOM series (GDCM).
// Origin, spacing and direction are honoured. `what` names the input in error messages.
#include "Core/Volume.h"
#include "Core/VolumeShelf.h"
#include "IO/ImageCheck.h"

#include <functional>
#include <memory>
#include <string>

namespace colonmap::io {

// Throws colonmap::Error ("<what> '<path>': <problem>") for a missing file, an unknown format,
// a folder without DICOM, a truncated or corrupt file, more than three axes, or non-finite /
// non-positive spacing. CheckImageFile (IO/ImageCheck.h) finds the same problems, in the same
// words, short of those only the voxels show, without reading them.
// `note` hears what the user should know about how the file was read (one line each, for stdout):
// axes stored with a negative spacing or a left-handed frame, read as flipped axes.
using NoteSink = std::function<void(const std::string&)>;
template <typename T>
Volume<T> ReadImage(const std::string& path, const std::string& what, const NoteSink& note = {});

// In a pipeline run in one process: the volume the stage before kept for `path` on the shelf
// (Core/VolumeShelf.h), else the file. Without a shelf, ReadImage.
template <typename T>
Volume<T> ReadImageKept(VolumeShelf* shelf, const std::string& path, const std::string& what,
                        const NoteSink& note = {}, ProgressSink* progress = nullptr) {
  if (shelf)
    if (std::optional<Volume<T>> kept = shelf->Take<T>(path, progress)) return std::move(*kept);
  return ReadImage<T>(path, what, note);
}

// The same for a stage that only reads the volume: shared with the shelf and the other readers
// (VolumeShelf::Share, no copy), else read from the file.
template <typename T>
std::shared_ptr<const Volume<T>> ReadImageShared(VolumeShelf* shelf, const std::string& path, const std::string& what,
                                                 const NoteSink& note = {}, ProgressSink* progress = nullptr) {
  if (shelf)
    if (std::shared_ptr<const Volume<T>> kept = shelf->Share<T>(path, progress)) return kept;
  return std::make_shared<const Volume<T>>(ReadImage<T>(path, what, note));
}

enum class Compression {
  Fast,  // gzip level 1: label maps and smooth images shrink 10-100x at little cost
  None,  // noisy CTs barely compress (0.54x) and gzip would take seconds at clinical size
};

// Writes the image; the format follows the extension.
template <typename T>
void WriteImage(const Volume<T>& image, const std::string& path, const std::string& what,
                Compression compression = Compression::Fast);

}  // namespace colonmap::io
