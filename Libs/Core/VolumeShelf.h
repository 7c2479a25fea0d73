#pragma once
// Volumes a pipeline's stage hands to the next one in memory (issue 22: ColonSupineProne runs
// its stages in one process). The stage still writes its file (the stage folders are the
// outputs); the next stage takes the volume from the shelf instead of reading the file back,
// which saves the read (ColonSurface read its label map, CT and virtual label in 0.5-2 s per
// clinical scan) and a long wait that Cancel could not interrupt.
//
// The pipeline says which files to keep and how many stages will read each (Expect); a stage
// that wrote such a file leaves a copy (Put); a stage about to read a file takes it (Take), as
// the type it asks for (converted like a reader would), and the last expected read moves it off
// the shelf, so nothing is held longer than needed. Files not expected are never kept. Safe to
// use from several threads (the two scans' jobs share one shelf).
#include "Core/Volume.h"

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace colonmap {

class VolumeShelf {
 public:
  void Expect(const std::string& path, int reads) {
    const std::lock_guard<std::mutex> lock(mutex_);
    entries_[path].reads = reads;
  }

  // Keeps the volume when `path` is expected: a stage hands over a volume it no longer needs
  // (moved in, no CT-sized copy).
  template <typename T>
  void Put(const std::string& path, Volume<T>&& volume) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      const auto it = entries_.find(path);
      if (it == entries_.end() || it->second.reads <= 0) return;
    }
    auto kept = std::make_shared<Kept>(std::move(volume));
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = entries_.find(path);
    if (it != entries_.end() && it->second.reads > 0) it->second.volume = std::move(kept);
  }

  // The volume kept for `path` as type T, or nothing. The copy or conversion runs outside the
  // lock, in pieces with `progress` (when given) polled between them.
  template <typename T>
  std::optional<Volume<T>> Take(const std::string& path, ProgressSink* progress = nullptr) {
    std::shared_ptr<Kept> kept;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      const auto it = entries_.find(path);
      if (it == entries_.end() || it->second.reads <= 0 || !it->second.volume) return std::nullopt;
      kept = it->second.volume;
      if (--it->second.reads == 0) entries_.erase(it);  // the last read: this call holds the only reference
    }
    const bool last = kept.use_count() == 1;
    std::optional<Volume<T>> out;
    std::visit(
        [&](auto& volume) {
          using K = std::decay_t<decltype(volume)>;
          if constexpr (std::is_same_v<K, Volume<T>>) {
            if (last) {
              out = std::move(volume);
              return;
            }
          }
          Volume<T> v = volume.template EmptyLike<T>();
          v.voxels.reserve(volume.voxels.size());
          ForPieces(volume.voxels.size(), kPollPiece, progress, [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) v.voxels.push_back(static_cast<T>(volume.voxels[i]));
          });
          out = std::move(v);
        },
        *kept);
    return out;
  }

 private:
  using Kept = std::variant<Volume<short>, Volume<unsigned char>, Volume<float>>;
  struct Entry {
    int reads = 0;
    std::shared_ptr<Kept> volume;  // shared with a Take that copies it outside the lock
  };
  std::mutex mutex_;
  std::map<std::string, Entry> entries_;
};

}  // namespace colonmap
