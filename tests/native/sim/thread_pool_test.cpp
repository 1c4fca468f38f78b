// Thesis §4.3 partitioning: contiguous chunks, the first N mod T one larger; every item exactly
// once per loop.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "sim/thread_pool.h"

using gaitlab::sim::ThreadPool;

TEST(ThreadPool, ChunksAreContiguousAndTheFirstRemainderOnesAreLarger) {
  for (int n = 0; n <= 23; ++n) {
    for (int t = 1; t <= 5; ++t) {
      int expectBegin = 0;
      for (int i = 0; i < t; ++i) {
        const auto r = ThreadPool::chunk(n, t, i);
        EXPECT_EQ(r.begin, expectBegin);
        EXPECT_EQ(r.end - r.begin, n / t + (i < n % t ? 1 : 0)) << "n=" << n << " t=" << t;
        expectBegin = r.end;
      }
      EXPECT_EQ(expectBegin, n);
    }
  }
}

TEST(ThreadPool, EveryItemIsVisitedExactlyOncePerLoop) {
  for (int threads = 1; threads <= 4; ++threads) {
    ThreadPool pool(threads);
    EXPECT_EQ(pool.size(), threads);
    for (int n : {0, 1, 2, 3, 7, 100}) {
      std::vector<std::atomic<int>> hits(n);
      for (int loop = 0; loop < 50; ++loop) {
        pool.parallelFor(n, [&](int b, int e, int) {
          for (int i = b; i < e; ++i) hits[i].fetch_add(1);
        });
      }
      for (int i = 0; i < n; ++i) EXPECT_EQ(hits[i].load(), 50) << "item " << i;
    }
  }
}

TEST(ThreadPool, ChunkTRunsOnThreadT) {
  ThreadPool pool(3);
  std::vector<int> owner(10, -1);
  pool.parallelFor(10, [&](int b, int e, int t) {
    for (int i = b; i < e; ++i) owner[i] = t;
  });
  for (int i = 0; i < 10; ++i) {
    int expected = 0;
    for (int t = 0; t < 3; ++t) {
      const auto r = ThreadPool::chunk(10, 3, t);
      if (i >= r.begin && i < r.end) expected = t;
    }
    EXPECT_EQ(owner[i], expected);
  }
}

TEST(ThreadPool, ForEachVisitsEveryItemOnceWhateverTheThreadCount) {
  for (int threads = 1; threads <= 4; ++threads) {
    ThreadPool pool(threads);
    for (int n : {0, 1, 2, 3, 12, 100}) {
      std::vector<std::atomic<int>> hits(n);
      for (int loop = 0; loop < 50; ++loop) pool.forEach(n, [&](int i) { hits[i].fetch_add(1); });
      for (int i = 0; i < n; ++i) EXPECT_EQ(hits[i].load(), 50) << "threads " << threads << " item " << i;
    }
  }
}

// The point of forEach (the physics shards in full mode): a thread held up in one item does not
// hold up the others, which the remaining thread takes. With fixed contiguous chunks, the item
// held up here would wait for items of its own chunk that nobody else may run.
TEST(ThreadPool, ForEachLetsTheFreeThreadTakeTheRestWhileOneIsHeldUp) {
  ThreadPool pool(2);
  constexpr int kItems = 12;
  std::atomic<int> done{0};
  bool othersFinishedMeanwhile = false;
  pool.forEach(kItems, [&](int i) {
    if (i == 0) {
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (done.load() < kItems - 1 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::yield();
      othersFinishedMeanwhile = done.load() == kItems - 1;
    } else {
      done.fetch_add(1);
    }
  });
  EXPECT_TRUE(othersFinishedMeanwhile);
}
