// The simple-point test against hand-made configurations and against an independent check:
// adding the centre to a neighbourhood set in an empty 5x5x5 block must keep the number of
// 26-components, of 6-components of the background, and the Euler characteristic.
#include "SegmentationTestUtils.h"
#include "Segmentation/EulerCharacteristic.h"
#include "Segmentation/SimplePoint.h"

#include <gtest/gtest.h>

#include <random>

using namespace colonmap;
using namespace colonmap::segmentation;
using namespace colonmap::segmentation::testing;

namespace {
std::uint32_t Bits(std::initializer_list<int> bits) {
  std::uint32_t m = 0;
  for (int b : bits) m |= 1u << b;
  return m;
}
Volume<unsigned char> Block(std::uint32_t neighbourhood, bool withCentre) {
  Volume<unsigned char> v;
  v.size = {{5, 5, 5}};
  v.Allocate(0);
  for (int b = 0; b < 27; ++b)
    if ((neighbourhood >> b) & 1u) v.At(1 + b % 3, 1 + (b / 3) % 3, 1 + b / 9) = 1;
  v.At(2, 2, 2) = withCentre ? 1 : 0;
  return v;
}
}  // namespace

TEST(SimplePoint, HandMadeConfigurations) {
  const int left = NeighbourBit(-1, 0, 0), right = NeighbourBit(1, 0, 0);
  EXPECT_FALSE(IsSimple26(0));                   // a new component
  EXPECT_TRUE(IsSimple26(Bits({left})));          // extends a component
  EXPECT_TRUE(IsSimple26(Bits({NeighbourBit(-1, -1, -1)})));  // vertex contact counts for 26
  EXPECT_FALSE(IsSimple26(Bits({left, right})));  // merges two components
  EXPECT_EQ(ForegroundComponents26(Bits({left, right})), 2);
  EXPECT_FALSE(IsSimple26((1u << 27) - 1));       // fills a one-voxel cavity
  EXPECT_EQ(BackgroundComponents6((1u << 27) - 1), 0);
  std::uint32_t ring = 0, below = 0;
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      if (di || dj) ring |= 1u << NeighbourBit(di, dj, 0);
      below |= 1u << NeighbourBit(di, dj, -1);
    }
  EXPECT_FALSE(IsSimple26(ring));  // closes a disk over a ring: the ring's hole disappears
  EXPECT_EQ(BackgroundComponents6(ring), 2);
  EXPECT_TRUE(IsSimple26(below));  // sits on a flat floor
  EXPECT_TRUE(IsSimple26(below | ring));
}

TEST(SimplePoint, AgreesWithGlobalTopologyOnRandomNeighbourhoods) {
  std::mt19937 random(7);
  int simple = 0, notSimple = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    const double density = (trial % 9 + 0.5) / 9.0;
    std::bernoulli_distribution bit(density);
    std::uint32_t n = 0;
    for (int b = 0; b < 27; ++b)
      if (b != 13 && bit(random)) n |= 1u << b;
    const Volume<unsigned char> without = Block(n, false), with = Block(n, true);
    const bool same = Components(without, 1) == Components(with, 1) &&
                      Components(without, 0) == Components(with, 0) &&
                      EulerCharacteristic(without) == EulerCharacteristic(with);
    ASSERT_EQ(IsSimple26(n), same) << "neighbourhood " << n;
    (same ? simple : notSimple)++;
  }
  EXPECT_GT(simple, 500);  // both kinds were exercised
  EXPECT_GT(notSimple, 500);
}

TEST(EulerCharacteristic, KnownShapes) {
  EXPECT_EQ(EulerCharacteristic(Shape(3, 3, 3, [](double, double, double) { return false; })), 0);
  EXPECT_EQ(EulerCharacteristic(Shape(3, 3, 3, [](double i, double j, double k) { return i == 1 && j == 1 && k == 1; })), 1);
  const auto ball = [](double i, double j, double k) {
    return (i - 10) * (i - 10) + (j - 10) * (j - 10) + (k - 10) * (k - 10) <= 64;
  };
  EXPECT_EQ(EulerCharacteristic(Shape(21, 21, 21, ball)), 1);
  EXPECT_EQ(EulerCharacteristic(Shape(21, 21, 21, [&](double i, double j, double k) {
              return ball(i, j, k) && (i - 10) * (i - 10) + (j - 10) * (j - 10) + (k - 10) * (k - 10) > 4;
            })), 2);  // one cavity
  EXPECT_EQ(EulerCharacteristic(Shape(30, 30, 12, [](double i, double j, double k) {
              const double r = std::hypot(i - 14.5, j - 14.5);
              return (r - 9) * (r - 9) + (k - 5.5) * (k - 5.5) <= 9;
            })), 0);  // solid torus
  // Two cubes touching at one vertex are one 26-component: chi = 1 + 1 - 1 (shared vertex).
  EXPECT_EQ(EulerCharacteristic(Shape(4, 4, 4, [](double i, double j, double k) {
              return (i == 1 && j == 1 && k == 1) || (i == 2 && j == 2 && k == 2);
            })), 1);
}
