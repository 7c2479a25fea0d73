#include "Views/StoppableRayCastMapper.h"

#include <vtkFiniteDifferenceGradientEstimator.h>
#include <vtkObjectFactory.h>
#include <vtkSphericalDirectionEncoder.h>

namespace colonmap::views {

namespace {

// VTK's spherical encoding of the gradient directions until the mapper is stopped, then the
// zero direction at once (the costly part of a gradient voxel is this encoding: atan2, asin).
class StoppableDirectionEncoder : public vtkSphericalDirectionEncoder {
 public:
  static StoppableDirectionEncoder* New();
  vtkTypeMacro(StoppableDirectionEncoder, vtkSphericalDirectionEncoder);

  void Watch(const std::atomic<bool>* stop) { stop_ = stop; }

  int GetEncodedDirection(float n[3]) override {
    if (stop_ && stop_->load(std::memory_order_relaxed)) return 0;
    return vtkSphericalDirectionEncoder::GetEncodedDirection(n);
  }

 protected:
  StoppableDirectionEncoder() = default;

 private:
  const std::atomic<bool>* stop_ = nullptr;
};

vtkStandardNewMacro(StoppableDirectionEncoder);

}  // namespace

vtkStandardNewMacro(StoppableRayCastMapper);

StoppableRayCastMapper::StoppableRayCastMapper() {
  // The base class made a plain spherical encoder, given to its gradient estimator as well (the
  // shading tables decode through that): both get ours, which decodes the same.
  StoppableDirectionEncoder* encoder = StoppableDirectionEncoder::New();
  encoder->Watch(&stop_);
  this->DirectionEncoder->Delete();
  this->DirectionEncoder = encoder;  // deleted by the base class
  this->GradientEstimator->SetDirectionEncoder(encoder);
}

}  // namespace colonmap::views
