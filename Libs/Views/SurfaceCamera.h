#pragma once
// A fixed overview camera for 3D pictures of the whole colon surface (issue 8, paper Figs. 11-12):
// parallel projection along a chosen anatomical direction, framed so that every given point
// lies inside the picture with a margin, and the pure geometry to predict where a point appears
// (tests, overlays). Eigen only; the VTK side is SurfaceRenderer.
//
// Directions are LPS (x to the patient's left, y posterior, z superior). The default view is
// anterior, as a radiologist faces the patient: the camera in front (at -P) looks along +P with
// superior up, so the patient's right is on the picture's left (Slicer's "Anterior" 3D view).
#include "Views/CameraPose.h"

#include <Eigen/Core>

#include <string>

namespace colonmap::views {

// A named overview direction: `viewDirection` is where the camera looks (unit, LPS), `viewUp`
// the picture's up.
struct SurfaceViewDirection {
  std::string name;
  Eigen::Vector3d viewDirection, viewUp;
};

// "anterior" (look along +P, up +S), "posterior" (along -P), "left" (camera at the patient's
// left looking along -L), "right" (along +L), "superior" (look along -S, up -P: from the head,
// the anterior wall at the top). Throws colonmap::Error for another name.
SurfaceViewDirection SurfaceViewNamed(const std::string& name);

struct SurfaceCamera {
  CameraPose pose;            // position, focal point (centre of the framed extent), view-up (unit, orthogonal to the view)
  double parallelScale = 1;   // half the picture height in mm (vtkCamera::SetParallelScale)
  double nearClip = 0, farClip = 1;  // distances from the camera enclosing all framed points
};

// The camera looking along view.viewDirection that frames all rows of `points` (n x 3, mm, n >= 1)
// in a picture of aspect width/height `aspect`: the extent of the points projected on the
// picture's right and up axes, centred, grown by `margin` (fraction of the half extent on each
// side; the tighter axis gets the margin, the other more). The camera stands outside the points
// (distance: the points' radius + 10% + 1 mm from the centre). Throws colonmap::Error for no
// points, non-finite values, aspect <= 0 or a view-up parallel to the view direction.
SurfaceCamera FrameSurface(const Eigen::MatrixXd& points, const SurfaceViewDirection& view, double aspect, double margin = 0.05);

// Where p appears in a width x height picture of `camera` (x right, y down, pixel centres at
// half-integers, as SurfaceRenderer's pictures).
Eigen::Vector2d ProjectParallel(const SurfaceCamera& camera, int width, int height, const Eigen::Vector3d& p);

}  // namespace colonmap::views
