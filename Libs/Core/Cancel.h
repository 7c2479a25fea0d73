#pragma once
// Cooperative cancellation and progress for long computations in Libs. A module passes a
// ProgressSink; Libs code calls Report() now and then (at least every 0.2 s of work) and stops
// by throwing Cancelled when the host asked to abort.
#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace colonmap {

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled by the host") {}
};

class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  // fraction in [0,1] of the current stage. Throws Cancelled when the host aborted.
  virtual void Report(double fraction) = 0;
};

// Maps a sub-step onto the range [from, to] of a parent's progress (several steps in one stage).
class SubProgress : public ProgressSink {
 public:
  SubProgress(ProgressSink& parent, double from, double to) : parent_(parent), from_(from), to_(to) {}
  void Report(double fraction) override {
    parent_.Report(from_ + (to_ - from_) * std::clamp(fraction, 0.0, 1.0));
  }

 private:
  ProgressSink& parent_;
  double from_, to_;
};

// A sink that ignores progress and never cancels, for tests and batch code.
class NullProgress : public ProgressSink {
 public:
  void Report(double) override {}
};

// A pass over [0, count) in pieces of `piece` items: body(begin, end) for each piece, then the
// done fraction reported. A pass over a CT-sized array (hundreds of MB, up to a second on a busy
// core) thereby still lets the host cancel within the 0.2 s above. With no sink, one piece.
template <typename Body>
void ForPieces(std::size_t count, std::size_t piece, ProgressSink* progress, Body&& body) {
  if (!progress || piece == 0) piece = count;
  for (std::size_t begin = 0; begin < count; begin += piece) {
    const std::size_t end = std::min(count, begin + piece);
    body(begin, end);
    if (progress) progress->Report(double(end) / double(count));
  }
}

// About 4M items (16 MB of floats): some 10 ms per piece for a simple pass.
constexpr std::size_t kPollPiece = std::size_t(1) << 22;

// `to` made a copy of the `count` items at `from`, in pieces, reporting between them; its new
// memory is first touched piece by piece too (no zero-filled resize of a CT-sized array first).
template <typename T, typename U>
void AssignReporting(const T* from, std::size_t count, std::vector<U>& to, ProgressSink* progress) {
  to.clear();
  to.reserve(count);
  ForPieces(count, kPollPiece, progress, [&](std::size_t b, std::size_t e) { to.insert(to.end(), from + b, from + e); });
}

// `to` made `count` copies of `value`, piece by piece (as AssignReporting).
template <typename T>
void FillReporting(std::vector<T>& to, std::size_t count, const T& value, ProgressSink* progress) {
  to.clear();
  to.reserve(count);
  ForPieces(count, kPollPiece, progress, [&](std::size_t b, std::size_t e) { to.insert(to.end(), e - b, value); });
}

// std::copy of `count` items in pieces, reporting between them.
template <typename T, typename U>
void CopyReporting(const T* from, std::size_t count, U* to, ProgressSink* progress) {
  ForPieces(count, kPollPiece, progress, [&](std::size_t b, std::size_t e) { std::copy(from + b, from + e, to + b); });
}

}  // namespace colonmap
