#pragma once
// Local repair of reversed faces of a registration's flat image (issue 7: the map must stay
// one-to-one). On surfaces from our own CT pipeline a flattening can hold a few reversed (or
// nearly degenerate) triangles, which any composed map inherits; a rigid guard (dropping
// constraints, shrinking h) cannot remove those. Here the images of the vertices of the bad faces
// and of `rings` rings of faces around them are replaced by the discrete harmonic (uniform
// weight, Tutte) interpolation of the images around that patch (end-loop vertices slide along
// their end line), which is one-to-one when the
// patch's rim is convex enough; a few rounds with growing rings are tried by the caller. Only the
// patch moves; everything else keeps its image. Eigen in and out.
#include <Eigen/Core>

#include <vector>

namespace colonmap::registration {

// image: n x 2 (modified in place), F: faces, badFaces: indices into F. Returns the number of
// vertices moved.
int RelaxAroundFaces(Eigen::MatrixXd& image, const Eigen::MatrixXi& F, const std::vector<Eigen::Index>& badFaces, int rings,
                     int iterations = 200);

}  // namespace colonmap::registration
