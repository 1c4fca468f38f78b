#include "sim/render_publisher.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <new>

namespace gaitlab::sim {

RenderPublisher::RenderPublisher() {
  // One block: header, two matrix buffers, body info; offsets are relative to the header so the
  // layout reads the same from JavaScript (a 32-bit address space) and from native tests.
  const size_t matrixBytes = sizeof(float) * 16 * kCapacity;
  const size_t total = sizeof(RenderHeader) + 2 * matrixBytes + sizeof(BodyInfo) * kCapacity;
  memory_.assign(total, 0);
  unsigned char* base = memory_.data();
  header_ = new (base) RenderHeader{};
  header_->capacity = kCapacity;
  header_->matrices[0] = sizeof(RenderHeader);
  header_->matrices[1] = static_cast<uint32_t>(sizeof(RenderHeader) + matrixBytes);
  header_->info = static_cast<uint32_t>(sizeof(RenderHeader) + 2 * matrixBytes);
  matrices_[0] = reinterpret_cast<float*>(base + header_->matrices[0]);
  matrices_[1] = reinterpret_cast<float*>(base + header_->matrices[1]);
  info_ = reinterpret_cast<BodyInfo*>(base + header_->info);
}

void RenderPublisher::add(btRigidBody* body, const BodyInfo& info) {
  info_[entries_.size()] = info;
  entries_.push_back({body, info});
  header_->infoVersion.fetch_add(1);
}

void RenderPublisher::addCharacter(const physics::Character& c, int id) {
  const body::Morphology& m = c.morphology();
  for (int i = 0; i < c.segmentCount(); ++i) {
    const body::Segment& s = m.segments[i];
    add(c.body(i), {{static_cast<float>(s.halfExtents.x()), static_cast<float>(s.halfExtents.y()),
                     static_cast<float>(s.halfExtents.z())},
                    s.rgba, id, 0});
  }
}

void RenderPublisher::remove(const std::vector<btRigidBody*>& bodies) {
  const auto gone = [&](const Entry& e) {
    return std::find(bodies.begin(), bodies.end(), e.body) != bodies.end();
  };
  entries_.erase(std::remove_if(entries_.begin(), entries_.end(), gone), entries_.end());
  for (size_t i = 0; i < entries_.size(); ++i) info_[i] = entries_[i].info;
  // After the entries: a reader that saw the old version reads them again (render_buffer.h).
  header_->infoVersion.fetch_add(1);
}

void RenderPublisher::rebind(int id, const physics::Character& c) {
  int k = 0;
  for (Entry& e : entries_)
    if (e.info.owner == id) e.body = c.body(k++);
}

void RenderPublisher::publish(uint32_t stepIndex, double time) {
  // Seqlock over two buffers (render_buffer.h): seq is bumped once when the writer starts on
  // the back buffer and once when it has published it, so a reader that sees seq advance by 2 or
  // more during its read knows the buffer it read may have been rewritten.
  const uint32_t back = 1 - header_->front.load(std::memory_order_relaxed);
  header_->seq.fetch_add(1, std::memory_order_acq_rel);
  float* m = matrices_[back];
  for (size_t i = 0; i < entries_.size(); ++i) {
    const btTransform& t = entries_[i].body->getCenterOfMassTransform();
    const btMatrix3x3& r = t.getBasis();
    const float* half = entries_[i].info.halfExtents;
    float* o = m + 16 * i;
    // Column-major 4x4 = [R * diag(2 * half) | p], three.js Matrix4.elements order.
    for (int col = 0; col < 3; ++col) {
      const float scale = 2.0f * half[col];
      for (int row = 0; row < 3; ++row) o[col * 4 + row] = static_cast<float>(r[row][col]) * scale;
      o[col * 4 + 3] = 0.0f;
    }
    o[12] = static_cast<float>(t.getOrigin().x());
    o[13] = static_cast<float>(t.getOrigin().y());
    o[14] = static_cast<float>(t.getOrigin().z());
    o[15] = 1.0f;
  }
  header_->bodyCount[back] = static_cast<uint32_t>(entries_.size());
  header_->stepIndex[back] = stepIndex;
  header_->simTime[back] = time;
  header_->front.store(back, std::memory_order_release);
  header_->seq.fetch_add(1, std::memory_order_release);
}

}  // namespace gaitlab::sim
