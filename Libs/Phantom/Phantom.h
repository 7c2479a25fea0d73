#pragma once
// Public entry points of the colon phantom (DESIGN 2, issue 3): a seeded colon anatomy, its
// supine and prone embeddings, the true wall meshes, ground-truth markups, dilatation
// statistics and synthetic CTs. Pure math: no I/O; the ColonPhantom module writes the files.
//
//   PhantomOptions o;                      // seed, deformation, fluid, spacing, mesh density
//   ColonAnatomy a = MakeAnatomy(o);
//   ScanGeometry sup = MakeScan(a, Posture::Supine, o), pro = MakeScan(a, Posture::Prone, o);
//   TriangleMesh ws = TrueWall(sup, o), wp = TrueWall(pro, o);
//   DilatationStats k = SummarizeDilatation(FaceDilatation(ws, wp), FaceSegments(ws));
//   Volume<short> ct = SynthesizeCT(sup, o, progress);
#include "ColonAnatomy.h"
#include "Dilatation.h"
#include "GroundTruth.h"
#include "PhantomOptions.h"
#include "ScanGeometry.h"
#include "SynthesizeCT.h"
#include "TrueWall.h"
#include "TubeLocator.h"
