// Long passes over CT-sized arrays in pieces, with the host polled between them (Core/Cancel.h).
#include "Core/Cancel.h"
#include "Core/Volume.h"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

namespace colonmap {
namespace {

// Records the fractions; throws Cancelled at the report numbered `cancelAt` (0: never).
struct Recording : ProgressSink {
  std::vector<double> fractions;
  std::size_t cancelAt = 0;
  void Report(double f) override {
    fractions.push_back(f);
    if (cancelAt && fractions.size() == cancelAt) throw Cancelled();
  }
};

TEST(Pieces, EachPieceOnceInOrderWithItsFractionAfterIt) {
  Recording sink;
  std::vector<std::pair<std::size_t, std::size_t>> pieces;
  ForPieces(10, 4, &sink, [&](std::size_t b, std::size_t e) { pieces.emplace_back(b, e); });
  EXPECT_EQ(pieces, (std::vector<std::pair<std::size_t, std::size_t>>{{0, 4}, {4, 8}, {8, 10}}));
  EXPECT_EQ(sink.fractions, (std::vector<double>{0.4, 0.8, 1.0}));
  pieces.clear();
  ForPieces(10, 4, nullptr, [&](std::size_t b, std::size_t e) { pieces.emplace_back(b, e); });
  EXPECT_EQ(pieces, (std::vector<std::pair<std::size_t, std::size_t>>{{0, 10}}));  // no sink: one pass
}

TEST(Pieces, CopiesAndFillsAreExactAndCancellable) {
  const std::size_t n = 3 * kPollPiece + 5;  // four pieces
  std::vector<short> from(n);
  std::iota(from.begin(), from.end(), short(0));
  Recording sink;
  std::vector<short> to;
  AssignReporting(from.data(), n, to, &sink);
  EXPECT_EQ(to, from);
  EXPECT_EQ(sink.fractions.size(), 4u);
  std::vector<float> converted(n);
  CopyReporting(from.data(), n, converted.data(), nullptr);
  EXPECT_EQ(converted[n - 1], float(from[n - 1]));

  Volume<short> grid;
  grid.size = {std::size_t(kPollPiece), 3, 1};
  Recording filling;
  const Volume<unsigned char> filled = grid.Like<unsigned char>(7, &filling);
  EXPECT_EQ(filled.voxels, std::vector<unsigned char>(grid.NumberOfVoxels(), 7));
  EXPECT_EQ(filling.fractions.size(), 3u);

  Recording cancelling;
  cancelling.cancelAt = 2;
  EXPECT_THROW(AssignReporting(from.data(), n, to, &cancelling), Cancelled);
  EXPECT_EQ(to.size(), 2 * kPollPiece);  // stopped after the second piece
}

}  // namespace
}  // namespace colonmap
