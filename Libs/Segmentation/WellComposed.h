#pragma once
// Making a binary voxel set well-composed (Latecki 1997) without changing its topology.
//
// Why: marching cubes (and flying edges) resolve the ambiguous cube configurations (a 2x2 face
// with only a diagonal pair set, a 2x2x2 cube with only a body-diagonal pair set or unset) by
// a fixed table. On a (26,6)-connected set, such as the topological ball the segmentation grows,
// that table joins what the set separates or separates what it joins: the contour can get
// handles or non-manifold edges the voxels do not have (measured on the GCA colon: genus 29 from
// a genus-0 ball contoured nearly unsmoothed). On a well-composed set no such configuration
// exists, so the iso-surface of any field with the set's sign pattern at the voxel centres is a
// closed manifold with the set's topology.
#include "Core/Cancel.h"
#include "Core/Volume.h"

namespace colonmap::segmentation {

// mask: 0/1, 26-connected foreground, voxels on the image border 0. Critical cubes are resolved
// by adding one of their unset voxels that is a simple point (SimplePoint.h: the set's topology
// never changes), pass after pass until no addition helps; the cubes left then get one of their
// set voxels removed (a simple point), and the additions resume. Each voxel changes at most
// once, so the repair ends. Returns the number of voxels changed. Throws colonmap::Error when
// critical cubes are left. Deterministic. `progress`, when given, is polled every few slices.
long MakeWellComposed(Volume<unsigned char>& mask, ProgressSink* progress = nullptr);

// The same without the Error: critical cubes no simple-point change can fix each lose a set
// voxel anyway (which may change the topology: the caller simplifies it again, see
// LumenTopology.h). Returns the voxels changed; *forced gets those removed that way.
long MakeWellComposedForcing(Volume<unsigned char>& mask, long* forced, ProgressSink* progress = nullptr);

// Number of critical (not well-composed) 2x2x2 cubes of a 0/1 mask; 0 after MakeWellComposed.
long CriticalCubes(const Volume<unsigned char>& mask);

}  // namespace colonmap::segmentation
