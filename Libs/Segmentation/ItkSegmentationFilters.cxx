// ITK side of Libs/Segmentation: no Eigen, no Core/Volume.h here (see the header).
#include "Segmentation/ItkSegmentationFilters.h"

#include "Core/Error.h"

#include <itkBinaryFillholeImageFilter.h>
#include <itkCommand.h>
#include <itkConnectedComponentImageFilter.h>
#include <itkImportImageFilter.h>
#include <itkSignedMaurerDistanceMapImageFilter.h>

#include <algorithm>
#include <exception>
#include <string>
#include <thread>

namespace colonmap::segmentation::detail {
namespace {

using MaskImage = itk::Image<unsigned char, 3>;

// Wraps a caller's buffer as an itk::Image without copying.
MaskImage::Pointer Wrap(const Grid& grid, const unsigned char* mask) {
  auto import = itk::ImportImageFilter<unsigned char, 3>::New();
  itk::ImportImageFilter<unsigned char, 3>::SizeType size;
  itk::ImportImageFilter<unsigned char, 3>::IndexType start;
  double spacing[3];
  for (int d = 0; d < 3; ++d) {
    size[d] = grid.size[d];
    start[d] = 0;
    spacing[d] = grid.spacing[d];
  }
  itk::ImportImageFilter<unsigned char, 3>::RegionType region;
  region.SetIndex(start);
  region.SetSize(size);
  import->SetRegion(region);
  import->SetSpacing(spacing);
  // ITK's import takes a non-const pointer; the filters below only read their input.
  import->SetImportPointer(const_cast<unsigned char*>(mask), grid.Count(), false);
  import->Update();
  MaskImage::Pointer image = import->GetOutput();
  image->DisconnectPipeline();
  return image;
}

// Forwards ITK's ProgressEvent to our sink, from the thread that runs Update() only (the sink
// is not thread-safe); a Cancelled (or any exception) from the sink asks the filter to abort and
// is rethrown after Update() returns.
class ForwardProgress : public itk::Command {
 public:
  using Self = ForwardProgress;
  using Pointer = itk::SmartPointer<Self>;
  itkNewMacro(Self);

  ProgressSink* sink = nullptr;
  std::thread::id owner;
  std::exception_ptr error;

  void Execute(itk::Object* caller, const itk::EventObject& event) override {
    Execute(static_cast<const itk::Object*>(caller), event);
    if (error) static_cast<itk::ProcessObject*>(caller)->AbortGenerateDataOn();
  }
  void Execute(const itk::Object* caller, const itk::EventObject& event) override {
    if (error || !itk::ProgressEvent().CheckEvent(&event) || std::this_thread::get_id() != owner) return;
    try {
      sink->Report(static_cast<const itk::ProcessObject*>(caller)->GetProgress());
    } catch (...) {
      error = std::current_exception();
    }
  }
};

void Run(itk::ProcessObject* filter, ProgressSink& progress, const char* what) {
  auto forward = ForwardProgress::New();
  forward->sink = &progress;
  forward->owner = std::this_thread::get_id();
  filter->AddObserver(itk::ProgressEvent(), forward);
  progress.Report(0.0);
  try {
    filter->Update();
  } catch (const itk::ProcessAborted&) {
    if (!forward->error) throw Error(std::string(what) + ": aborted");
  } catch (const itk::ExceptionObject& e) {
    if (!forward->error) throw Error(std::string(what) + ": " + e.GetDescription());
  }
  if (forward->error) std::rethrow_exception(forward->error);
  progress.Report(1.0);
}

}  // namespace

std::uint32_t ItkLabelComponents26(const Grid& grid, const unsigned char* mask, std::vector<std::uint32_t>& labels,
                                   ProgressSink& progress) {
  using LabelImage = itk::Image<std::uint32_t, 3>;
  auto filter = itk::ConnectedComponentImageFilter<MaskImage, LabelImage>::New();
  filter->SetInput(Wrap(grid, mask));
  filter->FullyConnectedOn();
  filter->SetBackgroundValue(0);
  SubProgress filtering(progress, 0.0, 0.9), copying(progress, 0.9, 1.0);
  Run(filter, filtering, "connected components");
  AssignReporting(filter->GetOutput()->GetBufferPointer(), grid.Count(), labels, &copying);
  return static_cast<std::uint32_t>(filter->GetObjectCount());
}

void ItkFillCavities6(const Grid& grid, std::vector<unsigned char>& mask, ProgressSink& progress) {
  auto filter = itk::BinaryFillholeImageFilter<MaskImage>::New();
  filter->SetInput(Wrap(grid, mask.data()));
  filter->SetForegroundValue(1);
  filter->FullyConnectedOff();  // holes are face-connected background: the 6 of (26,6)
  SubProgress filtering(progress, 0.0, 0.9), copying(progress, 0.9, 1.0);
  Run(filter, filtering, "cavity filling");
  CopyReporting(filter->GetOutput()->GetBufferPointer(), grid.Count(), mask.data(), &copying);
}

void InsideDistance(const Grid& grid, const unsigned char* mask, std::vector<float>& distance,
                    ProgressSink& progress) {
  using FloatImage = itk::Image<float, 3>;
  auto filter = itk::SignedMaurerDistanceMapImageFilter<MaskImage, FloatImage>::New();
  filter->SetInput(Wrap(grid, mask));
  filter->SetBackgroundValue(0);
  filter->InsideIsPositiveOn();
  filter->SquaredDistanceOff();
  filter->UseImageSpacingOn();
  SubProgress filtering(progress, 0.0, 0.9), copying(progress, 0.9, 1.0);
  Run(filter, filtering, "distance map");
  const float* out = filter->GetOutput()->GetBufferPointer();
  distance.clear();
  distance.reserve(grid.Count());  // filled piece by piece: its pages are first touched between reports
  ForPieces(grid.Count(), kPollPiece, &copying, [&](std::size_t b, std::size_t e) {
    for (std::size_t v = b; v < e; ++v) distance.push_back(mask[v] ? std::max(out[v], 0.0f) : 0.0f);
  });
}

}  // namespace colonmap::segmentation::detail
