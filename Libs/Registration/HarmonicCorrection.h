#pragma once
// The harmonic correction of DESIGN §2.4 (issue 7): on the supine segment, h = (h1, h2) harmonic
// (cotangent Laplacian of the 3D surface, glued across the periodic cut so that h is continuous
// around the colon) with h(p_k) = d_k at the constraint vertices (d_k = phi2(q_k) - eta(phi1(p_k))
// of matched features), h2 = 0 on the two end loops (the segment ends stay on the prone ends) and
// h1 free (Neumann) there. The corrected image is eta(phi1) + h. One-to-one guard: while the
// corrected flat image has reversed (or nearly degenerate) faces, the constraint groups nearest to them are dropped and
// h solved again; after `maxDropRounds` rounds h is halved until no face is reversed (h = 0, the
// affine map, is always one-to-one). Eigen in and out.
#include "Core/Cancel.h"
#include "Registration/SurfaceMap.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::registration {

struct FlatConstraint {
  int vertex = -1;                 // supine (cut mesh) vertex
  Eigen::Vector2d displacement{0, 0};  // wanted h there (flat units)
  int group = 0;                   // constraints of one matched feature are dropped together
};

struct HarmonicCorrectionOptions {
  int maxDropRounds = 6;
  // A face counts as bad (like a reversed one) when its corrected flat area is below this
  // fraction of its affine area: nearly degenerate images can face backwards on the prone
  // surface once mapped through phi2^-1.
  double minAreaRatio = 0.0;
};

struct HarmonicCorrectionResult {
  Eigen::MatrixXd h;               // n x 2 per supine vertex
  Eigen::MatrixXd imageUV;         // etaUV + scale * h, no reversed face
  std::vector<int> droppedGroups;  // groups removed by the one-to-one guard (ascending)
  int constraintsUsed = 0;         // distinct constrained vertices in the final solve
  int rounds = 0;                  // solves done
  double scale = 1.0;              // factor applied to h at the end (1 unless halving was needed)
  int surfaceRetries = 0;          // halvings of h by RegisterSegment's 3D orientation guard
  long initialFlips = 0;           // bad (reversed or nearly degenerate) faces of the first solve
};

// supine: flat uv (for the flip check and distances), F, 3D positions (Laplacian, gluing),
// period. etaUV: n x 2, the affine image eta(phi1) (must itself be one-to-one). Constraints on
// end-loop vertices keep h2 = 0 there. progress: Report(0..1), may throw Cancelled.
HarmonicCorrectionResult SolveHarmonicCorrection(const FlatSegment& supine, const Eigen::MatrixXd& etaUV,
                                                 const std::vector<FlatConstraint>& constraints,
                                                 const HarmonicCorrectionOptions& options, ProgressSink& progress);

}  // namespace colonmap::registration
