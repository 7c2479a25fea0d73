#pragma once
// Options of the colon phantom and the tissue model of its CT. Plain data; every output of the
// phantom is a pure function of these (same options -> bit-identical outputs).
#include <Eigen/Core>
#include <cstdint>

namespace colonmap {
namespace phantom {

enum class Posture { Supine, Prone };

// Segment ids as in DESIGN 3.3 (SegmentId point array): 0..4 = A, T, D, S, R.
enum SegmentId : int { kAscending = 0, kTransverse = 1, kDescending = 2, kSigmoid = 3, kRectum = 4 };
// Flexures in order from the cecum.
enum FlexureId : int { kHepatic = 0, kSplenic = 1, kDescendingSigmoid = 2, kSigmoidRectum = 3 };

inline const char* SegmentName(int id) {
  static constexpr const char* names[] = {"A", "T", "D", "S", "R"};
  return id >= 0 && id < 5 ? names[id] : "?";
}
inline const char* FlexureName(int id) {
  static constexpr const char* names[] = {"HF", "SF", "DSJ", "RSJ"};
  return id >= 0 && id < 4 ? names[id] : "?";
}
// Taeniae: libera, omentalis, mesocolica; index k sits at TaeniaTheta(k, s).
inline const char* TaeniaName(int k) {
  static constexpr const char* names[] = {"TL", "TO", "TM"};
  return k >= 0 && k < 3 ? names[k] : "?";
}

// Intensities (HU) and body geometry of the synthetic CT.
struct TissueModel {
  double airHU = -1000.0;
  double fatHU = -100.0;
  double softTissueHU = 40.0;    // skin/muscle rim of the body
  double wallHU = 40.0;          // colon wall
  double wallThicknessMm = 3.0;  // outer wall surface = distended base radius + this (folds are mucosal)
  double bodySemiAxisXMm = 172.0;  // elliptic abdomen, centred on the z axis
  double bodySemiAxisYMm = 135.0;
  double bodyRimMm = 12.0;       // soft-tissue rim inside the skin; fat inside it
  double noiseSigmaHU = 15.0;
  double blurSigmaVoxels = 0.35; // blur folded into the partial-volume profile (see SynthesizeCT.h)
  Eigen::Vector3d fieldOfViewMm{358.4, 358.4, 450.0};  // 512 x 512 x 450 at 0.7, 0.7, 1.0 mm
  Eigen::Vector3d fieldOfViewCentre{0.0, 0.0, -15.0};  // LPS mm
};

struct PhantomOptions {
  std::uint32_t seed = 1;
  double deformation = 0.5;            // 0: prone = supine geometry; 1: strong deformation
  bool fluid = true;                   // tagged fluid pools in the CT
  Eigen::Vector3d spacing{0.7, 0.7, 1.0};  // CT voxel spacing, mm
  double meshStepMm = 1.0;             // true-wall grid step along s
  int meshPointsAround = 160;          // true-wall grid points around (theta)
  int evaluationPoints = 200;          // evaluation wall points E001...
  int collapses = 0;                   // collapsed stretches (issue 21; Collapse.h), 0..4
  TissueModel tissue;
};

}  // namespace phantom
}  // namespace colonmap
