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

  template <typename T>
  void Put(const std::string& path, const Volume<T>& volume) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = entries_.find(path);
    if (it != entries_.end() && it->second.reads > 0) it->second.volume = volume;
  }

  template <typename T>
  std::optional<Volume<T>> Take(const std::string& path) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = entries_.find(path);
    if (it == entries_.end() || it->second.reads <= 0 || std::holds_alternative<std::monostate>(it->second.volume))
      return std::nullopt;
    const bool last = --it->second.reads == 0;
    std::optional<Volume<T>> out;
    std::visit(
        [&](auto& kept) {
          using K = std::decay_t<decltype(kept)>;
          if constexpr (std::is_same_v<K, Volume<T>>) {
            out = last ? std::move(kept) : kept;
          } else if constexpr (!std::is_same_v<K, std::monostate>) {
            Volume<T> v = kept.template Like<T>();
            for (std::size_t i = 0; i < kept.voxels.size(); ++i) v.voxels[i] = static_cast<T>(kept.voxels[i]);
            out = std::move(v);
          }
        },
        it->second.volume);
    if (last) entries_.erase(it);
    return out;
  }

 private:
  struct Entry {
    int reads = 0;
    std::variant<std::monostate, Volume<short>, Volume<unsigned char>, Volume<float>> volume;
  };
  std::mutex mutex_;
  std::map<std::string, Entry> entries_;
};

}  // namespace colonmap
