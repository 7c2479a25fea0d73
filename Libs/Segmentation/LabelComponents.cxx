#include "Segmentation/LabelComponents.h"

#include "Core/Error.h"

#include <algorithm>
#include <limits>

namespace colonmap::segmentation::detail {
namespace {

struct Run {
  std::uint32_t first, last;  // i of its first and last voxel
};

// Union-find over run indices; each set's root is its smallest index (its first run in raster
// order), so numbering the roots in index order numbers the components in raster order.
std::uint32_t Root(std::vector<std::uint32_t>& parent, std::uint32_t r) {
  std::uint32_t root = r;
  while (parent[root] != root) root = parent[root];
  while (parent[r] != root) {  // path compression
    const std::uint32_t next = parent[r];
    parent[r] = root;
    r = next;
  }
  return root;
}

void Join(std::vector<std::uint32_t>& parent, std::uint32_t a, std::uint32_t b) {
  a = Root(parent, a);
  b = Root(parent, b);
  if (a < b) parent[b] = a;
  else if (b < a) parent[a] = b;
}

}  // namespace

std::uint32_t LabelComponents26(const Grid& grid, const unsigned char* mask, std::vector<std::uint32_t>& labels,
                                ProgressSink& progress, bool labelsOfOne) {
  const std::size_t n0 = grid.size[0], n1 = grid.size[1], n2 = grid.size[2];
  const std::size_t rows = n1 * n2;
  // 1. The runs of each row (row r = j + n1 k), in raster order.
  std::vector<Run> runs;
  std::vector<std::size_t> rowStart(rows + 1, 0);
  for (std::size_t r = 0; r < rows; ++r) {
    if (r % n1 == 0 && (r / n1) % 4 == 0) progress.Report(0.3 * double(r) / double(rows));
    rowStart[r] = runs.size();
    const unsigned char* row = mask + r * n0;
    for (std::size_t i = 0; i < n0;) {
      if (!row[i]) {
        ++i;
        continue;
      }
      const std::size_t first = i;
      while (i < n0 && row[i]) ++i;
      runs.push_back({static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(i - 1)});
    }
    if (runs.size() >= std::numeric_limits<std::uint32_t>::max()) throw Error("connected components: too many runs");
  }
  rowStart[rows] = runs.size();

  // 2. Links: a run touches a run of an earlier row (j-1 in its slice; j-1, j, j+1 in the slice
  // before) when their i ranges overlap or meet diagonally.
  std::vector<std::uint32_t> parent(runs.size());
  for (std::uint32_t r = 0; r < parent.size(); ++r) parent[r] = r;
  const auto link = [&](std::size_t row, std::size_t other) {
    std::size_t a = rowStart[row], b = rowStart[other];
    const std::size_t aEnd = rowStart[row + 1], bEnd = rowStart[other + 1];
    while (a < aEnd && b < bEnd) {
      const Run& x = runs[a];
      const Run& y = runs[b];
      if (std::uint64_t(x.last) + 1 < y.first) {
        ++a;
      } else if (std::uint64_t(y.last) + 1 < x.first) {
        ++b;
      } else {
        Join(parent, static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
        if (x.last < y.last) ++a;  // the one ending first can touch nothing further
        else ++b;
      }
    }
  };
  for (std::size_t k = 0; k < n2; ++k) {
    if (k % 4 == 0) progress.Report(0.3 + 0.3 * double(k) / double(n2));
    for (std::size_t j = 0; j < n1; ++j) {
      const std::size_t row = j + n1 * k;
      if (rowStart[row] == rowStart[row + 1]) continue;
      if (j > 0) link(row, row - 1);
      if (k > 0)
        for (std::size_t jj = j > 0 ? j - 1 : 0; jj <= std::min(j + 1, n1 - 1); ++jj) link(row, jj + n1 * (k - 1));
    }
  }

  // 3. Numbers: each root in index order, then every run its root's number. parent[r] <= r, so
  // in index order a run's parent already points at its root, and a root is numbered before the
  // runs under it (the numbers overwrite the parents in place).
  for (std::size_t r = 0; r < parent.size(); ++r) parent[r] = parent[parent[r]];
  std::vector<std::uint32_t>& number = parent;
  std::uint32_t count = 0;
  for (std::size_t r = 0; r < number.size(); ++r) number[r] = parent[r] == r ? ++count : number[parent[r]];
  labels.clear();
  if (count == 1 && !labelsOfOne) {
    progress.Report(1.0);
    return count;
  }
  // 4. The label grid, slice by slice (its memory first touched between polls).
  labels.reserve(grid.Count());
  const std::size_t slice = n0 * n1;
  for (std::size_t k = 0; k < n2; ++k) {
    if (k % 4 == 0) progress.Report(0.6 + 0.4 * double(k) / double(n2));
    labels.resize(labels.size() + slice, 0u);
    for (std::size_t j = 0; j < n1; ++j) {
      const std::size_t row = j + n1 * k;
      std::uint32_t* out = labels.data() + row * n0;
      for (std::size_t r = rowStart[row]; r < rowStart[row + 1]; ++r)
        std::fill(out + runs[r].first, out + runs[r].last + 1, number[r]);
    }
  }
  progress.Report(1.0);
  return count;
}

}  // namespace colonmap::segmentation::detail
