#include "sim/ids.h"

namespace gaitlab::sim {

int IdPool::create(int value) {
  int slot;
  if (!free_.empty()) {
    slot = free_.back();
    free_.pop_back();
  } else if (static_cast<int>(slots_.size()) < kSlots) {
    slot = static_cast<int>(slots_.size());
    slots_.emplace_back();
  } else {
    return -1;
  }
  Slot& s = slots_[slot];
  s.used = true;
  s.value = value;
  return s.generation << kSlotBits | slot;
}

void IdPool::destroy(int id) {
  if (!live(id)) return;
  Slot& s = slots_[slotOf(id)];
  s.used = false;
  s.value = -1;
  // The next occupant gets the next generation; a slot whose generations are used up retires.
  if (++s.generation < kGenerations) free_.push_back(slotOf(id));
}

bool IdPool::live(int id) const {
  if (id < 0) return false;
  const int slot = slotOf(id);
  return slot < static_cast<int>(slots_.size()) && slots_[slot].used &&
         slots_[slot].generation == generationOf(id);
}

}  // namespace gaitlab::sim
