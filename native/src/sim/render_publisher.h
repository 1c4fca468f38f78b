// Publishing the scene for drawing: every body's transform written into the render buffer the
// browser's main thread reads straight out of shared memory (render_buffer.h gives the layout
// and the seqlock), and the static BodyInfo of each body, kept in step with the scene as bodies
// come and go.
#pragma once
#include <cstdint>
#include <vector>

#include "physics/character.h"
#include "sim/render_buffer.h"

class btRigidBody;

namespace gaitlab::sim {

class RenderPublisher {
 public:
  static constexpr int kCapacity = 16384;  // bodies

  RenderPublisher();
  RenderPublisher(const RenderPublisher&) = delete;
  RenderPublisher& operator=(const RenderPublisher&) = delete;

  const RenderHeader* header() const { return header_; }
  int count() const { return static_cast<int>(entries_.size()); }
  bool hasRoom(int bodies) const { return count() + bodies <= kCapacity; }
  // The bodies in render order: the order they were added, removals packed out.
  const btRigidBody* body(int i) const { return entries_[i].body; }

  void add(btRigidBody* body, const BodyInfo& info);
  // Every body of a character, owned by `id`, in its segments' order.
  void addCharacter(const physics::Character& c, int id);
  // Drops the entries of `bodies` and packs the rest (owners and order kept).
  void remove(const std::vector<btRigidBody*>& bodies);
  // Points the entries of character `id` at the bodies of `c`, a new figure of the same
  // morphology (a reset): the entries keep their places and colours.
  void rebind(int id, const physics::Character& c);

  // Writes every transform into the back buffer and flips it to the front.
  void publish(uint32_t stepIndex, double time);

 private:
  struct Entry {
    btRigidBody* body;
    BodyInfo info;
  };
  std::vector<Entry> entries_;
  std::vector<unsigned char> memory_;  // header + 2 matrix buffers + body info
  RenderHeader* header_ = nullptr;
  float* matrices_[2] = {nullptr, nullptr};
  BodyInfo* info_ = nullptr;
};

}  // namespace gaitlab::sim
