#pragma once
// Test helper: a flattened segment with a known answer, the unit-width strip [0,1] x [0,length]
// (period 1) on a straight cylinder of circumference 100 mm, so one flat unit is 100 mm. nu x nv
// quads, two triangles each; the cut copies (u = 0 and u = 1) coincide exactly in 3D.
#include "Registration/SurfaceMap.h"

#include <cmath>

namespace colonmap::registration::testing {

inline FlatSegment CylinderSegment(int nu, int nv, double length) {
  FlatSegment s;
  s.period = 1.0;
  s.uv.resize((nu + 1) * (nv + 1), 2);
  s.position.resize(s.uv.rows(), 3);
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const int k = j * (nu + 1) + i;
      s.uv.row(k) << double(i) / nu, length * j / nv;
      const double a = 2 * M_PI * (i == nu ? 0 : double(i) / nu);
      s.position.row(k) << 100 / (2 * M_PI) * std::cos(a), 100 / (2 * M_PI) * std::sin(a), 100 * length * j / nv;
    }
  s.F.resize(2 * nu * nv, 3);
  int f = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
      s.F.row(f++) << a, b, d;
      s.F.row(f++) << a, d, c;
    }
  return s;
}

}  // namespace colonmap::registration::testing
