// Which surface vertices bound virtual lumen (issue 21): a vertex with a virtual voxel among the
// eight around it.
#include "Surface/VirtualWall.h"

#include <gtest/gtest.h>

using namespace colonmap;

TEST(VirtualWall, VerticesNextToVirtualVoxelsOnly) {
  Volume<unsigned char> m;
  m.size = {{10, 10, 10}};
  m.spacing = Eigen::Vector3d(2, 2, 2);
  m.origin = Eigen::Vector3d(-10, 0, 0);
  m.Allocate(0);
  m.At(5, 5, 5) = 1;  // the voxel centred at (0, 10, 10)
  Eigen::MatrixXd V(5, 3);
  V << 0.5, 10.5, 10.5,   // in the cell whose corner is the virtual voxel
      -1.5, 8.5, 8.5,     // the cell below: (4,4,4)..(5,5,5), corner (5,5,5) virtual
      -2.5, 10, 10,       // cell (3..4): no virtual corner
      3, 14, 14,          // far
      100, 100, 100;      // outside the image
  const Eigen::VectorXd v = surface::VirtualVertices(V, m);
  EXPECT_EQ(v(0), 1.0);
  EXPECT_EQ(v(1), 1.0);
  EXPECT_EQ(v(2), 0.0);
  EXPECT_EQ(v(3), 0.0);
  EXPECT_EQ(v(4), 0.0);
}
