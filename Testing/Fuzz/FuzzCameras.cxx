// ReadCameras (cameras.json, --cameras input). Contract when it returns: at least one view, all
// coordinates finite, a camera that looks somewhere (focal point != position) with a view-up not
// along the view direction (VTK would build a degenerate view matrix from it).
#include "FuzzCommon.h"
#include "Views/CameraJson.h"
#include "Core/Error.h"

#include <Eigen/Geometry>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fuzz::WriteInput(data, size, ".json");
  try {
    const auto cameras = colonmap::views::ReadCameras(path, "cameras");
    if (cameras.empty()) fuzz::Violation("no cameras returned");
    for (const auto& c : cameras) {
      const auto& p = c.pose;
      if (!p.position.allFinite() || !p.focalPoint.allFinite() || !p.viewUp.allFinite())
        fuzz::Violation("camera coordinate not finite");
      const Eigen::Vector3d d = p.focalPoint - p.position;
      if (!(d.norm() > 0.0)) fuzz::Violation("camera focal point equals its position");
      if (!(d.normalized().cross(p.viewUp).norm() > 1e-9 * p.viewUp.norm()) || !(p.viewUp.norm() > 0.0))
        fuzz::Violation("camera view-up is zero or along the view direction");
    }
  } catch (const colonmap::Error&) {
  }
  return 0;
}
