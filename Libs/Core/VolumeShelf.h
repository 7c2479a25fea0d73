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
// the shelf, so nothing is held longer than needed; a stage that only reads it shares it (Share:
// no copy, held until the last reader is done). Files not expected are never kept. Safe to
// use from several threads (the two scans' jobs share one shelf).
#include "Core/Volume.h"

#include <atomic>
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
    const std::shared_ptr<Kept> kept = TakeShared(path);
    if (!kept) return std::nullopt;
    if (auto* same = std::get_if<Volume<T>>(kept.get()); same && kept.use_count() == 1) {
      // The last read, and no other Take still copies it nor a sharer holds it (their pointers
      // count too): move it out. The fence orders that copier's reads (its reference's release)
      // before our writes.
      std::atomic_thread_fence(std::memory_order_acquire);
      return std::move(*same);
    }
    return Converted<T>(*kept, progress);
  }

  // Lets go of what is kept for `path`, read or not (a stage expected to read it did not run):
  // sharers keep theirs.
  void Drop(const std::string& path) {
    const std::lock_guard<std::mutex> lock(mutex_);
    entries_.erase(path);
  }

  // The volume kept for `path`, to read only, or null: the kept volume itself when it is kept
  // as T (no copy: the readers of one CT share it, and it lives until the last of them lets go),
  // else converted as Take does.
  template <typename T>
  std::shared_ptr<const Volume<T>> Share(const std::string& path, ProgressSink* progress = nullptr) {
    const std::shared_ptr<Kept> kept = TakeShared(path);
    if (!kept) return nullptr;
    if (const auto* same = std::get_if<Volume<T>>(kept.get())) return std::shared_ptr<const Volume<T>>(kept, same);
    return std::make_shared<const Volume<T>>(Converted<T>(*kept, progress));
  }

  // The same with each voxel mapped by `map` (e.g. a label map to a 0/1 mask of one label).
  template <typename T, typename Map>
  std::optional<Volume<T>> TakeMapped(const std::string& path, Map map, ProgressSink* progress = nullptr) {
    const std::shared_ptr<Kept> kept = TakeShared(path);
    if (!kept) return std::nullopt;
    return std::visit([&](const auto& volume) { return MapVoxels<T>(volume, map, progress); }, *kept);
  }

 private:
  using Kept = std::variant<Volume<short>, Volume<unsigned char>, Volume<float>>;

  // A copy of a kept volume as pixel type T (each voxel cast, as a reader converts).
  template <typename T>
  static Volume<T> Converted(const Kept& kept, ProgressSink* progress) {
    return std::visit([&](const auto& volume) { return MapVoxels<T>(volume, [](auto v) { return static_cast<T>(v); }, progress); },
                      kept);
  }

  struct Entry {
    int reads = 0;
    std::shared_ptr<Kept> volume;  // shared with a Take that copies it outside the lock
  };
  std::shared_ptr<Kept> TakeShared(const std::string& path) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = entries_.find(path);
    if (it == entries_.end() || it->second.reads <= 0 || !it->second.volume) return nullptr;
    std::shared_ptr<Kept> kept = it->second.volume;
    if (--it->second.reads == 0) entries_.erase(it);
    return kept;
  }

  std::mutex mutex_;
  std::map<std::string, Entry> entries_;
};

}  // namespace colonmap
