#pragma once
// VTK's fixed-point volume ray caster, stoppable part way through a picture (a Cancel need not
// wait for it). Included by EndoluminalRenderer.cxx only: VTK stays out of the public headers.
//
// Most of a picture's time goes to the gradients of the whole cropped CT, which VTK 9.1 computes
// with no abort check (its ray casting checks the window's abort flag at every row). Stop() makes
// the rest of that pass trivial: every direction is left unencoded from then on. The caller also
// sets the window's abort flag, so the casting ends at its next row. The picture is then garbage
// and must be thrown away; Rearm() before the next one. Until Stop() the pictures are VTK's own,
// bit for bit.
#include <vtkFixedPointVolumeRayCastMapper.h>

#include <atomic>

namespace colonmap::views {

class StoppableRayCastMapper : public vtkFixedPointVolumeRayCastMapper {
 public:
  static StoppableRayCastMapper* New();
  vtkTypeMacro(StoppableRayCastMapper, vtkFixedPointVolumeRayCastMapper);

  // From any thread, also from within the gradient pass (an observer of its progress events).
  void Stop() { stop_.store(true, std::memory_order_relaxed); }
  void Rearm() { stop_.store(false, std::memory_order_relaxed); }
  bool Stopped() const { return stop_.load(std::memory_order_relaxed); }

 protected:
  StoppableRayCastMapper();
  ~StoppableRayCastMapper() override = default;

 private:
  std::atomic<bool> stop_{false};  // read by the encoder on every voxel of the gradient pass
};

}  // namespace colonmap::views
