// gaitlab's own collision algorithms in Bullet's dispatcher: boxes on the terrain's relief
// (physics/terrain.cpp) and boxes on the ground plane (physics/discrete_world.cpp).
#pragma once
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>

#include <new>

namespace gaitlab::physics {

// Makes `dispatcher` build an `Algorithm` for every pair of a `first` and a `second` shape type,
// in either order. The algorithm is built in the dispatcher's pool, as Bullet's own are, by
// Algorithm(constructionInfo, wrapper0, wrapper1, swapped), where `swapped` says that wrapper0
// holds the `second` shape. The factories hold nothing but their order, so one pair serves every
// world.
template <class Algorithm>
void registerCollisionAlgorithm(btCollisionDispatcher& dispatcher, int first, int second) {
  struct CreateFunc : btCollisionAlgorithmCreateFunc {
    explicit CreateFunc(bool swapped) { m_swapped = swapped; }
    btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                   const btCollisionObjectWrapper* w0,
                                                   const btCollisionObjectWrapper* w1) override {
      void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(Algorithm));
      return new (memory) Algorithm(ci, w0, w1, m_swapped);
    }
  };
  static CreateFunc inOrder(false), swapped(true);
  dispatcher.registerCollisionCreateFunc(first, second, &inOrder);
  dispatcher.registerCollisionCreateFunc(second, first, &swapped);
}

}  // namespace gaitlab::physics
