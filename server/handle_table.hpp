#pragma once
// A dense table addressed by generation-counted handles (the slot map of game engines): items sit
// contiguously, so a stage loops over `items()` with no gaps or null checks; a handle names an
// item through an indirection slot whose generation changes when the item goes, so a handle kept
// past a removal (a fighter's target, a session's avatar) reads as gone instead of as whoever
// took the place. Adding and removing are O(1); removal moves the last item into the gap.
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace foresight::server {

struct Handle {
  uint32_t slot = std::numeric_limits<uint32_t>::max();
  uint32_t generation = 0;
  bool operator==(const Handle&) const = default;
};

template <typename T>
class HandleTable {
 public:
  void reserve(size_t n) {
    items_.reserve(n);
    item_slot_.reserve(n);
    slots_.reserve(n);
  }

  Handle add(T item) {
    uint32_t slot;
    if (free_slots_.empty()) {
      slot = static_cast<uint32_t>(slots_.size());
      slots_.push_back({});
    } else {
      slot = free_slots_.back();
      free_slots_.pop_back();
    }
    slots_[slot].index = static_cast<uint32_t>(items_.size());
    items_.push_back(std::move(item));
    item_slot_.push_back(slot);
    return {slot, slots_[slot].generation};
  }

  /// Removes the item (no-op for a stale handle); returns it so the caller decides when its memory
  /// goes.
  T remove(Handle h) {
    const uint32_t index = index_of(h);
    if (index == kNone) return T{};
    T removed = std::move(items_[index]);
    const uint32_t last = static_cast<uint32_t>(items_.size()) - 1;
    if (index != last) {
      items_[index] = std::move(items_[last]);
      item_slot_[index] = item_slot_[last];
      slots_[item_slot_[index]].index = index;
    }
    items_.pop_back();
    item_slot_.pop_back();
    ++slots_[h.slot].generation;
    free_slots_.push_back(h.slot);
    return removed;
  }

  T* get(Handle h) {
    const uint32_t index = index_of(h);
    return index == kNone ? nullptr : &items_[index];
  }
  const T* get(Handle h) const {
    const uint32_t index = index_of(h);
    return index == kNone ? nullptr : &items_[index];
  }
  /// The handle of items()[index].
  Handle handle_at(size_t index) const {
    const uint32_t slot = item_slot_[index];
    return {slot, slots_[slot].generation};
  }

  std::span<T> items() { return items_; }
  std::span<const T> items() const { return items_; }
  size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }

 private:
  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  struct Slot {
    uint32_t index = kNone;
    uint32_t generation = 0;
  };
  uint32_t index_of(Handle h) const {
    if (h.slot >= slots_.size() || slots_[h.slot].generation != h.generation) return kNone;
    return slots_[h.slot].index;
  }

  std::vector<T> items_;
  std::vector<uint32_t> item_slot_;  ///< items_[i]'s slot.
  std::vector<Slot> slots_;
  std::vector<uint32_t> free_slots_;
};

}  // namespace foresight::server
