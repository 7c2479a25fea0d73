// RingAverage (Surface/RingAverage.h) on known answers.
#include "Surface/RingAverage.h"

#include <gtest/gtest.h>

using colonmap::surface::RingAverage;

// Two triangles (0,1,2), (0,2,3): the rings (the vertex after each vertex in its faces) are
// 0: {1, 2}, 1: {2}, 2: {0, 3}, 3: {0}, so one pass of 0, 3, 6, 9 gives 3, 4.5, 5, 4.5.
TEST(RingAverage, OnePassIsTheMeanOfTheVertexAndItsRing) {
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 2, 3;
  Eigen::MatrixXd x(4, 2);
  x << 0, 1, 3, 1, 6, 1, 9, 1;
  const Eigen::MatrixXd once = RingAverage(F, x, 1);
  EXPECT_DOUBLE_EQ(once(0, 0), 3.0);
  EXPECT_DOUBLE_EQ(once(1, 0), 4.5);
  EXPECT_DOUBLE_EQ(once(2, 0), 5.0);
  EXPECT_DOUBLE_EQ(once(3, 0), 4.5);
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(once(i, 1), 1.0);  // a constant stays
  EXPECT_EQ(RingAverage(F, x, 0), x);
  // Two passes are one pass of one pass; the values draw together.
  const Eigen::MatrixXd twice = RingAverage(F, x, 2);
  EXPECT_TRUE(twice.isApprox(RingAverage(F, once, 1)));
  EXPECT_LT(twice.col(0).maxCoeff() - twice.col(0).minCoeff(), once.col(0).maxCoeff() - once.col(0).minCoeff());
}
