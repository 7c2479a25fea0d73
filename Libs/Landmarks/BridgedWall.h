#pragma once
// Where the colon's wall was not seen (issue 21): ColonSegmentation bridged a collapsed stretch
// with virtual lumen and ColonSurface marked that wall Virtual = 1. A flexure found there was
// found on the smooth virtual tube, not on the colon (the bend of a collapsed flexure is cut:
// a splenic flexure 38 mm off on tube seed 6), so the joint choice takes the other scan's.
//
// A place inside the colon is on bridged wall when the level set of the along-colon function
// through its nearest wall vertex is mostly virtual: the level sets are loops around the colon,
// all virtual inside a bridged stretch and all real outside it.
#include "Core/TriangleMesh.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::landmarks {

// mesh: the closed colon surface (point array Virtual optional), alongColon: its along-colon
// function (one value per vertex, 0..1), points: q x 3 places inside the lumen. Returns q flags,
// all false without a Virtual array. bins: level sets grouped into this many bins of f.
std::vector<bool> OnBridgedWall(const TriangleMesh& mesh, const Eigen::VectorXd& alongColon,
                                const Eigen::MatrixXd& points, int bins = 1000);

}  // namespace colonmap::landmarks
