// Stable generational ids for the things of a scene (characters and props), as Box2D v3 names
// its bodies (b2BodyId: an index into the world's body array and a generation). An id names a
// slot and the generation of that slot's current occupant: when a thing is removed its slot's
// generation advances, so the old id stops naming anything, and a later thing that reuses the
// slot gets a different id. Lookup is an array index, not a search over the characters.
//
// Ids stay non-negative ints (the page, the render buffer's BodyInfo::owner and window.gaitlab
// treat them as opaque numbers; -1 means "none" or "all" there): generation << kSlotBits | slot.
// A fresh slot starts at generation 0 and slots are handed out in order until one is freed, so
// the first things of a scene get ids 0, 1, 2... as they always have.
#pragma once
#include <cstdint>
#include <vector>

namespace gaitlab::sim {

class IdPool {
 public:
  static constexpr int kSlotBits = 16;
  static constexpr int kSlots = 1 << kSlotBits;  // things alive at once (the render buffer holds 16384 bodies)
  // Generations a slot goes through before it is retired rather than reused: 2^15, so that
  // generation << kSlotBits stays below 2^31. A retired slot is never handed out again, which
  // is what makes "an id is never reused" hold for ever, not only for 2^15 removals.
  static constexpr int kGenerations = 1 << (31 - kSlotBits);

  // A new id whose value() is `value`; -1 when every slot is in use or retired.
  int create(int value);
  // How many more ids create() can hand out now.
  int room() const { return static_cast<int>(free_.size()) + kSlots - static_cast<int>(slots_.size()); }
  // Frees the slot of `id` (nothing if `id` is not live).
  void destroy(int id);
  // Whether `id` names a live thing: its slot is in use by that very generation.
  bool live(int id) const;
  // The value stored with a live id, or -1 for an id that names nothing.
  int value(int id) const { return live(id) ? slots_[slotOf(id)].value : -1; }
  void setValue(int id, int value) {
    if (live(id)) slots_[slotOf(id)].value = value;
  }

  static int slotOf(int id) { return id & (kSlots - 1); }
  static int generationOf(int id) { return id >> kSlotBits; }

 private:
  struct Slot {
    int generation = 0;
    int value = -1;
    bool used = false;
  };
  std::vector<Slot> slots_;
  std::vector<int> free_;  // freed slots, reused last-freed first
};

}  // namespace gaitlab::sim
