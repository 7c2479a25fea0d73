#include "IO/ItkImageBridge.h"
#include "IO/ImageCheck.h"
#include "IO/FileNames.h"
#include "IO/DicomCheck.h"
#include "IO/MetaImageCheck.h"
#include "IO/NiftiCheck.h"
#include "IO/NrrdCheck.h"

#include "Core/Error.h"

#include <itkGDCMImageIO.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageIOFactory.h>
#include <itkMultiThreaderBase.h>
#include <itkImageSeriesReader.h>
#include <itkMetaDataObject.h>

#include <gdcmTrace.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace colonmap::io::detail {
namespace {

template <typename T>
using ItkImage = itk::Image<T, 3>;

std::string OneLine(const itk::ExceptionObject& e) {
  std::string s = e.GetDescription();
  // "ITK ERROR: NrrdImageIO(0x55..): what went wrong": the object's address tells the user nothing.
  if (s.rfind("ITK ERROR: ", 0) == 0 || s.rfind("itk::ERROR: ", 0) == 0)
    if (const std::size_t at = s.find("): "); at != std::string::npos) s.erase(0, at + 3);
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// In-process, Slicer hands over images as "slicer:0x..#vtkMRMLScalarVolumeNode1", which only
// its own ImageIO (registered with ITK's factory) understands.
bool IsHostPath(const std::string& path) { return path.rfind("slicer:", 0) == 0; }

std::string Millimetres(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", v);
  return b;
}

// Of a row-major 3 x 3 matrix.
double Determinant(const double* m) {
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
}

// ITK's exception in our words, the same for a header read and a full read.
Error ReadError(const std::string& path, const std::string& what, const itk::ExceptionObject& e) {
  const std::string m = OneLine(e);
  if (m.find("Could not create IO object") != std::string::npos)
    return InputError(what, path, "unknown or unsupported image format");
  return InputError(what, path, "cannot be read (" + m + ")");
}

// What is checked before ITK opens the path: that it is there, and each format's own header
// check. Returns the axes stored with a negative spacing.
std::vector<int> DoorChecks(const std::string& path, const std::string& what) {
  if (path.empty()) throw Error(what + ": no file given");
  // ITK's warnings (several lines on stderr) must not come before our one line (issue 24); what
  // matters in them is checked here and said in that line.
  itk::Object::GlobalWarningDisplayOff();
  if (IsHostPath(path)) return {};
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(what, path, "file does not exist");
  std::vector<int> negativeAxes;
  for (const std::vector<int>& axes : {CheckNrrdHeader(path, what), CheckMetaImageFile(path, what), CheckNiftiFile(path, what)})
    if (!axes.empty()) negativeAxes = axes;
  return negativeAxes;
}

// The files of the series a DICOM folder means, checked before GDCM opens any of them.
std::vector<std::string> DicomSeriesFiles(const std::string& folder, const std::string& what) {
  // GDCM's own log (10 lines and more on a bad file) must not come before our one line; what
  // matters in it is checked here and said in that line.
  gdcm::Trace::WarningOff();
  gdcm::Trace::ErrorOff();
  gdcm::Trace::DebugOff();
  // Before GDCM opens any file: it aborts the process on a slice cut short, and drops a slice of
  // another size into a series of its own.
  CheckDicomFolder(folder, what);
  // Look for a DICOM file first: GDCMSeriesFileNames warns on stderr when there is none.
  bool anyDicom = false;
  auto probe = itk::GDCMImageIO::New();
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_regular_file(ec) && probe->CanReadFile(entry.path().c_str())) {
      anyDicom = true;
      break;
    }
  }
  if (!anyDicom) throw InputError(what, folder, "folder holds no DICOM series");
  auto names = itk::GDCMSeriesFileNames::New();
  names->SetUseSeriesDetails(true);
  names->SetDirectory(folder);
  const auto& uids = names->GetSeriesUIDs();
  if (uids.empty()) throw InputError(what, folder, "folder holds no DICOM series");
  // The series with most slices is the volume a user means when pointing at a folder.
  std::string best;
  std::size_t bestCount = 0;
  for (const auto& uid : uids) {
    const std::size_t n = names->GetFileNames(uid).size();
    if (n > bestCount) { best = uid; bestCount = n; }
  }
  return names->GetFileNames(best);
}

// Without `voxels`, only the headers of the first and last slice are read (size, spacing, frame).
template <typename T>
typename ItkImage<T>::Pointer ReadDicomSeries(const std::string& folder, const std::string& what, bool voxels) {
  auto reader = itk::ImageSeriesReader<ItkImage<T>>::New();
  reader->SetImageIO(itk::GDCMImageIO::New());
  reader->SetFileNames(DicomSeriesFiles(folder, what));
  if (!voxels) {
    reader->UpdateOutputInformation();
    return reader->GetOutput();
  }
  reader->Update();
  // A missing slice or uneven slice positions: ITK averages the z spacing and only warns (issue
  // 24); a measurement along z would then be wrong without a word. ITK measures it on the voxel read.
  typename ItkImage<T>::Pointer image = reader->GetOutput();
  double deviation = 0.0;
  if (itk::ExposeMetaData<double>(image->GetMetaDataDictionary(), "ITK_non_uniform_sampling_deviation", deviation) &&
      deviation > 0.1 * image->GetSpacing()[2])
    throw InputError(what, folder, "slices are not evenly spaced (a slice missing or out of place): positions deviate by " +
                                       Millimetres(deviation) + " mm from the mean spacing " +
                                       Millimetres(image->GetSpacing()[2]) + " mm");
  return image;
}

// ITK reads the first volume of a 4-D file (a time series, several echoes) into a 3-D image
// without a word.
void CheckThreeAxes(const std::string& path, const std::string& what, const itk::ImageIOBase& io) {
  const unsigned n = io.GetNumberOfDimensions();
  bool extra = false;
  std::string sizes;
  for (unsigned d = 0; d < n; ++d) {
    sizes += (d ? " x " : "") + std::to_string(io.GetDimensions(d));
    extra = extra || (d >= 3 && io.GetDimensions(d) > 1);
  }
  if (extra)
    throw InputError(what, path, "is a " + std::to_string(n) + "-D image (" + sizes + " voxels), not a 3-D volume");
}

template <typename T>
ImageGeometry GeometryOf(const ItkImage<T>& image) {
  ImageGeometry g;
  const auto size = image.GetLargestPossibleRegion().GetSize();
  for (unsigned d = 0; d < 3; ++d) {
    g.size[d] = size[d];
    g.spacing[d] = image.GetSpacing()[d];
    g.origin[d] = image.GetOrigin()[d];
    for (unsigned e = 0; e < 3; ++e) g.direction[3 * d + e] = image.GetDirection()[d][e];
  }
  return g;
}

// A geometry no stage can work with; known from the header, so the door check finds it too.
void CheckGeometry(const std::string& path, const std::string& what, const ImageGeometry& g) {
  const auto finite = [](const double* v, int n) { return std::all_of(v, v + n, [](double x) { return std::isfinite(x); }); };
  if (g.size[0] * g.size[1] * g.size[2] == 0) throw InputError(what, path, "image has no voxels");
  for (double s : g.spacing)
    if (!std::isfinite(s) || s <= 0.0) throw InputError(what, path, "voxel spacing is not a positive finite number");
  if (!finite(g.origin, 3) || !finite(g.direction, 9) || std::abs(Determinant(g.direction)) < 1e-6)
    throw InputError(what, path, "image origin or direction is not valid");
}

// The one note on how the file's axes were read: axes stored with a negative spacing (read as
// positive spacings along flipped axes, as ITK and Slicer do), or a left-handed frame.
void NoteFlippedAxes(const std::string& path, const std::string& what, std::vector<int> axes, ImageGeometry& g) {
  for (unsigned d = 0; d < 3; ++d)
    if (g.spacing[d] < 0.0) {  // a reader that kept the sign: flip the axis ourselves
      g.spacing[d] = -g.spacing[d];
      for (unsigned e = 0; e < 3; ++e) g.direction[3 * e + d] = -g.direction[3 * e + d];
      if (std::find(axes.begin(), axes.end(), int(d) + 1) == axes.end()) axes.push_back(int(d) + 1);
    }
  std::sort(axes.begin(), axes.end());
  const double det = Determinant(g.direction);
  std::string list;
  for (int a : axes) list += (list.empty() ? "" : ", ") + std::to_string(a);
  if (!axes.empty())
    g.notes.push_back(what + " '" + path + "': negative voxel spacing on axis " + list +
                      " in the file: read as a positive spacing with that axis flipped");
  else if (det < 0.0)
    g.notes.push_back(what + " '" + path + "': its axes form a left-handed frame (one axis stored flipped): read as stored");
}

// Reads the voxels straight into `into` through the file's ImageIO when they need no conversion
// (the pixel type T, one component, three axes): no second CT-sized buffer (on this machine new
// memory costs about 1 s per GB to fault in). Returns false when ImageFileReader must convert.
template <typename T>
bool ReadVoxelsDirectly(itk::ImageIOBase& io, std::vector<T>& into) {
  if (io.GetComponentType() != itk::ImageIOBase::MapPixelType<T>::CType || io.GetNumberOfComponents() != 1 ||
      io.GetNumberOfDimensions() != 3)
    return false;
  itk::ImageIORegion region(3);
  std::size_t n = 1;
  for (unsigned d = 0; d < 3; ++d) {
    region.SetIndex(d, 0);
    region.SetSize(d, io.GetDimensions(d));
    n *= io.GetDimensions(d);
  }
  io.SetIORegion(region);
  into.resize(n);
  io.Read(into.data());
  return true;
}

// The one read path of the header-only check and the full read, so that a problem is found by
// the same code and said in the same words by both. Without `voxels`, ITK reads the header only;
// with `into`, the voxels go there (directly when they can, else through the returned image).
template <typename T>
typename ItkImage<T>::Pointer ReadItkImage(const std::string& path, const std::string& what, bool voxels, ImageGeometry& g,
                                           std::vector<T>* into = nullptr) {
  const std::vector<int> negativeAxes = DoorChecks(path, what);
  typename ItkImage<T>::Pointer image;
  try {
    std::error_code ec;
    if (!IsHostPath(path) && fs::is_directory(path, ec)) {
      image = ReadDicomSeries<T>(path, what, voxels);
      into = nullptr;
    } else {
      auto reader = itk::ImageFileReader<ItkImage<T>>::New();
      reader->SetFileName(path);
      reader->UpdateOutputInformation();
      CheckThreeAxes(path, what, *reader->GetImageIO());
      if (voxels && !(into && ReadVoxelsDirectly<T>(*reader->GetImageIO(), *into))) {
        reader->Update();
        into = nullptr;  // the voxels are in the image
      }
      image = reader->GetOutput();  // its geometry is read either way
    }
  } catch (const itk::ExceptionObject& e) {
    throw ReadError(path, what, e);
  }
  g = GeometryOf<T>(*image);
  NoteFlippedAxes(path, what, negativeAxes, g);
  CheckGeometry(path, what, g);
  if (voxels && into) return nullptr;  // read directly
  return image;
}

}  // namespace

template <typename T>
void ItkReadImage(const std::string& path, const std::string& what, ImageGeometry& g, std::vector<T>& voxels) {
  const auto image = ReadItkImage<T>(path, what, /*voxels=*/true, g, &voxels);
  if (!image) return;  // read straight into `voxels`
  const std::size_t n = g.size[0] * g.size[1] * g.size[2];
  voxels.assign(image->GetBufferPointer(), image->GetBufferPointer() + n);
}

template <typename T>
void ItkWriteImage(const ImageGeometry& g, const T* voxels, const std::string& path, const std::string& what,
                   bool compress) {
  auto image = ItkImage<T>::New();
  typename ItkImage<T>::RegionType region;
  typename ItkImage<T>::SpacingType spacing;
  typename ItkImage<T>::PointType origin;
  typename ItkImage<T>::DirectionType direction;
  for (unsigned d = 0; d < 3; ++d) {
    region.SetSize(d, g.size[d]);
    spacing[d] = g.spacing[d];
    origin[d] = g.origin[d];
    for (unsigned e = 0; e < 3; ++e) direction[d][e] = g.direction[3 * d + e];
  }
  image->SetRegions(region);
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
  // Wrap the caller's buffer instead of copying it (clinical CTs are hundreds of MB).
  const std::size_t n = g.size[0] * g.size[1] * g.size[2];
  image->GetPixelContainer()->SetImportPointer(const_cast<T*>(voxels), n, false);
  try {
    auto writer = itk::ImageFileWriter<ItkImage<T>>::New();
    writer->SetFileName(path);
    writer->SetInput(image);
    writer->SetUseCompression(compress);
    if (compress) writer->SetCompressionLevel(1);  // fastest gzip: much quicker than the default 6
    writer->Update();
  } catch (const itk::ExceptionObject& e) {
    const std::string m = OneLine(e);
    if (m.find("Could not create IO object") != std::string::npos)
      throw InputError(what, path, "unknown or unsupported image format");
    throw InputError(what, path, "cannot be written (" + m + ")");
  }
}

// The pixel types the pipeline uses: CT (HU), label maps, float images.
#define COLONMAP_INSTANTIATE(T)                                                                   \
  template void ItkReadImage<T>(const std::string&, const std::string&, ImageGeometry&, std::vector<T>&); \
  template void ItkWriteImage<T>(const ImageGeometry&, const T*, const std::string&, const std::string&, bool);
COLONMAP_INSTANTIATE(short)
COLONMAP_INSTANTIATE(unsigned char)
COLONMAP_INSTANTIATE(float)
#undef COLONMAP_INSTANTIATE

void ItkPrepareForThreads() {
  itk::Image<short, 3>::New();
  itk::MultiThreaderBase::New();
  itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads();
  // Write mode goes by the extension alone (read mode would look for such a file).
  itk::ImageIOFactory::CreateImageIO("prepare.nrrd", itk::ImageIOFactory::FileModeEnum::WriteMode);
}

}  // namespace colonmap::io::detail

namespace colonmap::io {

void CheckImageFile(const std::string& path, const std::string& what) {
  // In-process, the host's own ImageIO reads the image from its scene: nothing to check here.
  if (detail::IsHostPath(path)) return;
  detail::ImageGeometry g;
  detail::ReadItkImage<short>(path, what, /*voxels=*/false, g);
}

}  // namespace colonmap::io
