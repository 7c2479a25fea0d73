#pragma once
// Parameters of electronic cleansing (DESIGN §2.1). Defaults suit CT colonography with oral
// contrast: air -1000 HU, soft tissue/wall about 40 HU, tagged fluid several hundred HU.
#include <Eigen/Core>

namespace colonmap::cleansing {

struct CleansingParameters {
  double airHU = -1000.0;            // the value cleansed material becomes
  double airThresholdHU = -800.0;    // below: confidently air
  double tagThresholdHU = 200.0;     // above: tagged material (or bone, told apart by air contact)
  double wallHU = 40.0;              // soft tissue the fluid lies on
  int partialVolumeVoxels = 2;       // reach of the partial-volume layers around tagged cores
  // Gravity ("down") in LPS; zero means estimate it from the air-fluid levels.
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
};

}  // namespace colonmap::cleansing
