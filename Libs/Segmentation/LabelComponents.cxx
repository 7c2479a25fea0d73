#include "Segmentation/LabelComponents.h"

#include "Core/Error.h"

#include <algorithm>
#include <limits>

namespace colonmap::segmentation::detail {
namespace {

using Run = ComponentRuns::Run;

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

// 1. The runs of each row, in raster order (labels not yet set): voxel i of row r is set when
// inside(r * n0 + i). Reports [0, 0.5].
template <typename Inside>
ComponentRuns FindRuns(const Grid& grid, Inside inside, ProgressSink& progress) {
  const std::size_t n0 = grid.size[0], n1 = grid.size[1], rows = grid.size[1] * grid.size[2];
  ComponentRuns c;
  c.rowStart.assign(rows + 1, 0);
  for (std::size_t r = 0; r < rows; ++r) {
    if (r % n1 == 0 && (r / n1) % 4 == 0) progress.Report(0.5 * double(r) / double(rows));
    c.rowStart[r] = c.runs.size();
    const std::size_t offset = r * n0;
    for (std::size_t i = 0; i < n0;) {
      if (!inside(offset + i)) {
        ++i;
        continue;
      }
      const std::size_t first = i;
      while (i < n0 && inside(offset + i)) ++i;
      c.runs.push_back({static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(i - 1), 0});
    }
    if (c.runs.size() >= std::numeric_limits<std::uint32_t>::max()) throw Error("connected components: too many runs");
  }
  c.rowStart[rows] = c.runs.size();
  return c;
}

// 2-3. Links and labels, 26-connected (full) or 6-connected. Reports [0.5, 1].
void LinkRuns(const Grid& grid, ComponentRuns& c, bool full, ProgressSink& progress) {
  const std::size_t n1 = grid.size[1], n2 = grid.size[2];
  const std::vector<Run>& runs = c.runs;
  const std::vector<std::size_t>& rowStart = c.rowStart;
  // 26: a run touches a run of an earlier row (j-1 in its slice; j-1, j, j+1 in the slice
  // before) when their i ranges overlap or meet diagonally. 6: rows j-1 and the same row of the
  // slice before, i ranges overlapping.
  const std::uint64_t reach = full ? 1 : 0;
  std::vector<std::uint32_t> parent(runs.size());
  for (std::uint32_t r = 0; r < parent.size(); ++r) parent[r] = r;
  const auto link = [&](std::size_t row, std::size_t other) {
    std::size_t a = rowStart[row], b = rowStart[other];
    const std::size_t aEnd = rowStart[row + 1], bEnd = rowStart[other + 1];
    while (a < aEnd && b < bEnd) {
      const Run& x = runs[a];
      const Run& y = runs[b];
      if (std::uint64_t(x.last) + reach < y.first) {
        ++a;
      } else if (std::uint64_t(y.last) + reach < x.first) {
        ++b;
      } else {
        Join(parent, static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
        if (x.last < y.last) ++a;  // the one ending first can touch nothing further
        else ++b;
      }
    }
  };
  for (std::size_t k = 0; k < n2; ++k) {
    if (k % 4 == 0) progress.Report(0.5 + 0.5 * double(k) / double(n2));
    for (std::size_t j = 0; j < n1; ++j) {
      const std::size_t row = j + n1 * k;
      if (rowStart[row] == rowStart[row + 1]) continue;
      if (j > 0) link(row, row - 1);
      if (k > 0 && full)
        for (std::size_t jj = j > 0 ? j - 1 : 0; jj <= std::min(j + 1, n1 - 1); ++jj) link(row, jj + n1 * (k - 1));
      else if (k > 0)
        link(row, row - n1);
    }
  }
  // Numbers: each root in index order, then every run its root's number. parent[r] <= r, so in
  // index order a run's parent already points at its root, and a root is numbered before the
  // runs under it.
  for (std::size_t r = 0; r < parent.size(); ++r) parent[r] = parent[parent[r]];
  c.count = 0;
  for (std::size_t r = 0; r < parent.size(); ++r) c.runs[r].label = parent[r] == r ? ++c.count : c.runs[parent[r]].label;
}

}  // namespace

ComponentRuns LabelComponentRuns26(const Grid& grid, const unsigned char* mask, ProgressSink& progress) {
  ComponentRuns c = FindRuns(grid, [mask](std::size_t v) { return mask[v] != 0; }, progress);
  LinkRuns(grid, c, true, progress);
  progress.Report(1.0);
  return c;
}

ComponentRuns LabelComponentRunsBelow26(const Grid& grid, const short* values, short threshold, ProgressSink& progress) {
  ComponentRuns c = FindRuns(grid, [values, threshold](std::size_t v) { return values[v] < threshold; }, progress);
  LinkRuns(grid, c, true, progress);
  progress.Report(1.0);
  return c;
}

std::uint32_t LabelComponents26(const Grid& grid, const unsigned char* mask, std::vector<std::uint32_t>& labels,
                                ProgressSink& progress, bool labelsOfOne) {
  SubProgress runStep(progress, 0.0, 0.6), gridStep(progress, 0.6, 1.0);
  const ComponentRuns c = LabelComponentRuns26(grid, mask, runStep);
  labels.clear();
  if (c.count == 1 && !labelsOfOne) {
    progress.Report(1.0);
    return c.count;
  }
  // The label grid, slice by slice (its memory first touched between polls).
  const std::size_t n0 = grid.size[0], n1 = grid.size[1], n2 = grid.size[2];
  labels.reserve(grid.Count());
  for (std::size_t k = 0; k < n2; ++k) {
    if (k % 4 == 0) gridStep.Report(double(k) / double(n2));
    labels.resize(labels.size() + n0 * n1, 0u);
    for (std::size_t j = 0; j < n1; ++j) {
      const std::size_t row = j + n1 * k;
      std::uint32_t* out = labels.data() + row * n0;
      for (std::size_t r = c.rowStart[row]; r < c.rowStart[row + 1]; ++r)
        std::fill(out + c.runs[r].first, out + c.runs[r].last + 1, c.runs[r].label);
    }
  }
  progress.Report(1.0);
  return c.count;
}

void FillCavities6(const Grid& grid, std::vector<unsigned char>& mask, ProgressSink& progress) {
  const std::size_t n0 = grid.size[0], n1 = grid.size[1], n2 = grid.size[2];
  SubProgress runStep(progress, 0.0, 0.9), fillStep(progress, 0.9, 1.0);
  unsigned char* m = mask.data();
  ComponentRuns background = FindRuns(grid, [m](std::size_t v) { return m[v] == 0; }, runStep);
  LinkRuns(grid, background, false, runStep);
  // The background's components that reach the border stay; the others are cavities.
  std::vector<bool> outside(background.count + 1, false);
  for (std::size_t row = 0; row + 1 < background.rowStart.size(); ++row) {
    const std::size_t j = row % n1, k = row / n1;
    const bool borderRow = j == 0 || k == 0 || j + 1 == n1 || k + 1 == n2;
    for (std::size_t r = background.rowStart[row]; r < background.rowStart[row + 1]; ++r) {
      const Run& run = background.runs[r];
      if (borderRow || run.first == 0 || run.last + 1 == n0) outside[run.label] = true;
    }
  }
  for (std::size_t row = 0; row + 1 < background.rowStart.size(); ++row) {
    if (row % (4 * n1) == 0) fillStep.Report(double(row) / double(n1 * n2));
    for (std::size_t r = background.rowStart[row]; r < background.rowStart[row + 1]; ++r) {
      const Run& run = background.runs[r];
      if (!outside[run.label]) std::fill(m + row * n0 + run.first, m + row * n0 + run.last + 1, 1);
    }
  }
  progress.Report(1.0);
}

}  // namespace colonmap::segmentation::detail
