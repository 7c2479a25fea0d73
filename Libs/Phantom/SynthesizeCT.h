#pragma once
// Synthetic CT colonography of one scan (int16 HU, LPS, identity direction).
// Body: an elliptic abdomen (soft-tissue rim, fat inside, air outside) extruded along z; colon
// wall of soft tissue between the lumen surface r(s, theta) and the outer wall surface; lumen
// air, or tagged fluid below a flat level in each pool (options.fluid).
// Partial volume and blur: each boundary contributes a smooth step of its signed distance d,
// S(d), the C1 cubic with the slope of a Gaussian-blurred box of one voxel (sigma_e^2 =
// h^2/12 + (blurSigmaVoxels h)^2, h = mean spacing), so S = 1/2 exactly on the true surface.
// For locally planar boundaries this equals box-sampling then Gaussian blurring; the noise is
// white, approximately Gaussian (sigma noiseSigmaHU), hashed from (seed, posture, voxel).
// Deterministic and independent of the number of threads.
#include "PhantomOptions.h"
#include "ScanGeometry.h"

#include <Core/Cancel.h>
#include <Core/Volume.h>

#include <Eigen/Core>

namespace colonmap {
namespace phantom {

// Empty image (no voxels allocated) covering options.tissue.fieldOfView at options.spacing.
Volume<short> CTGrid(const PhantomOptions& options);

// Half-width W (mm) of the partial-volume step: S(d) = 0 for d <= -W, 1 for d >= W.
double PartialVolumeHalfWidth(const PhantomOptions& options);
// The partial-volume step.
double PartialVolumeStep(double d, double halfWidth);

// HU of the body without the colon at p (LPS mm): air outside the elliptic abdomen (centred on
// the z axis), the soft-tissue rim, fat inside, with the partial-volume step of half-width W.
double BodyHU(const Eigen::Vector3d& p, const TissueModel& tissue, double W);

// CT on CTGrid(options). Calls progress.Report() per slab of slices (outside parallel regions).
Volume<short> SynthesizeCT(const ScanGeometry& scan, const PhantomOptions& options, ProgressSink& progress);
// Same, on a caller's grid (origin, spacing, size, direction set; voxels are (re)allocated).
void SynthesizeCTOnGrid(const ScanGeometry& scan, const PhantomOptions& options, Volume<short>& grid,
                        ProgressSink& progress);

// Lumen mask on CTGrid(options): 1 inside the closed lumen (air or fluid), 0 elsewhere.
Volume<unsigned char> LumenLabel(const ScanGeometry& scan, const PhantomOptions& options, ProgressSink& progress);

}  // namespace phantom
}  // namespace colonmap
