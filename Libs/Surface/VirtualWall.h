#pragma once
// Which vertices of a lumen surface lie on virtual wall (issue 21): wall of the virtual lumen
// that ColonSegmentation draws through a collapsed stretch, not seen in the CT. A vertex is
// virtual when any of the eight voxels around it (the trilinear neighbourhood of its position)
// is virtual lumen: the surface there bounds virtual lumen on its inner side.
#include "Core/Volume.h"

#include <Eigen/Core>

namespace colonmap::surface {

// V: n x 3 vertex positions (LPS mm); virtualLumen: non-zero where the lumen is virtual, any
// geometry. Returns n values, 1 for a virtual vertex and 0 otherwise (vertices outside the
// image are 0).
Eigen::VectorXd VirtualVertices(const Eigen::MatrixXd& V, const Volume<unsigned char>& virtualLumen);

}  // namespace colonmap::surface
