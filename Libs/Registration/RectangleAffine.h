#pragma once
// The affine rectangle-to-rectangle map eta of DESIGN §2.4 (the "conformal map only" baseline):
// u' = u + shift (a cyclic shift around the colon, period = the flat width), v' = v0' + scale (v - v0)
// (the supine length [v0, v1] onto the prone length [v0', v1']). And the cyclic shift that best
// aligns two mean-curvature images around the colon (circular cross-correlation along u), used
// when the two scans were cut along different taeniae. Eigen and Core in and out.
#include "Core/Volume.h"

#include <Eigen/Core>

namespace colonmap::registration {

struct RectangleAffine {
  double shift = 0.0;   // added to u
  double scale = 1.0;   // prone length / supine length
  double v0 = 0.0;      // supine v of the anal end
  double v0Target = 0.0;  // prone v of the anal end
  Eigen::Vector2d Apply(const Eigen::Vector2d& uv) const {
    return {uv.x() + shift, v0Target + scale * (uv.y() - v0)};
  }
  Eigen::Vector2d Inverse(const Eigen::Vector2d& uv) const {
    return {uv.x() - shift, v0 + (uv.y() - v0Target) / scale};
  }
  Eigen::MatrixXd Apply(const Eigen::MatrixXd& uv) const;  // row-wise
};

// eta for two flat maps (n x 2 each): scale = ratio of the v ranges, given shift. Throws
// colonmap::Error when a v range is empty.
RectangleAffine FitRectangleAffine(const Eigen::MatrixXd& supineUV, const Eigen::MatrixXd& proneUV, double shift);

struct CyclicShift {
  double shift = 0.0;           // in units of the width (-0.5, 0.5]: prone u = supine u + shift
  double correlation = 0.0;     // normalised cross-correlation at that shift
  double correlationAtZero = 0.0;
};
// Both images (nx around, ny along, 1 slice; any sizes) are resampled to `around` x `along`
// pixels over their own rectangle (periodic in x), normalised to zero mean and unit variance,
// and circularly correlated along x. Throws colonmap::Error for an empty image.
CyclicShift CyclicShiftByCorrelation(const Volume<float>& supine, const Volume<float>& prone, int around = 64,
                                     int along = 128);

}  // namespace colonmap::registration
