#pragma once
// Repair of faces whose 3D image faces against the target surface although their flat image is
// not reversed (issue 7: the map must stay one-to-one on the surface as it is stored, per vertex).
// A map kept per vertex draws each source face as the straight triangle through its three
// corners' images. Where that triangle straddles target triangles of very different shape (the
// slivers that cutting the colon open at a flexure leaves next to the end loops, or the long
// chords of an intrinsic Delaunay triangulation), the straight triangle can face backwards while
// every piece of the flat map is orientation-preserving. Measured on 10 phantom seeds: one such
// face in 3 of 50 segments, always next to an end loop; flat relaxation cannot see it and halving
// the harmonic correction down to zero did not remove it.
// Here a few interior corners of such faces are moved, one at a time, to the candidate flat
// position (on the way to the centroid of its neighbours' images or to one of them) that makes
// every face around it face the right way in both the flat domain and 3D, choosing the candidate
// whose worst face is best. Vertices on the source's boundary stay (the rectangle and the seam).
// Eigen in and out.
#include "Registration/SurfaceMap.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::registration {

// Whether face f's 3D image (the straight triangle through its corners' images `position`) faces
// along the target surface's normals interpolated at those images (`normal`, per source vertex).
bool ImageFacesAlongSurface(const Eigen::MatrixXi& F, Eigen::Index f, const Eigen::MatrixXd& position,
                            const Eigen::MatrixXd& normal);

// image: n x 2 source vertices' points in the target's flat domain (modified in place); F: source
// faces; target: the target's flat mesh with 3D positions; targetNormals: its vertex normals;
// position, normal: the current images' 3D points and interpolated target normals (n x 3);
// badFaces: faces that fail ImageFacesAlongSurface. Returns the number of vertices moved (0: no
// candidate helped).
int RepairSurfaceFlips(Eigen::MatrixXd& image, const Eigen::MatrixXi& F, const FlatSegment& target,
                       const Eigen::MatrixXd& targetNormals, const Eigen::MatrixXd& position, const Eigen::MatrixXd& normal,
                       const std::vector<Eigen::Index>& badFaces);

}  // namespace colonmap::registration
