// Thesis §4.3 partitioning: contiguous chunks, the first N mod T one larger; every item exactly
// once per loop.
#include <gtest/gtest.h>

#include <atomic>
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
