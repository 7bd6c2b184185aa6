// The task threads (linear_algebra/run_tasks.h): every task once, nested
// batches and concurrent callers run, exceptions reach the caller, and the
// measurements that moved onto them give the same bits on any number of
// parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <tuple>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "deform/deform.h"
#include "deform/quality.h"
#include "labels/nearest_labels.h"
#include "linear_algebra/run_tasks.h"
#include "mesh/sort_by_vertex.h"
#include "mesh/triangulate.h"
#include "test_meshes.h"

namespace {

using namespace polycube;

TEST(RunTasks, EveryTaskRunsOnceInEveryBatch) {
  for (int batch = 0; batch < 2000; ++batch) {
    const int count = 1 + batch % 7;
    std::vector<std::atomic<int>> runs(count);
    run_tasks(count, [&](int i) { ++runs[i]; });
    for (int i = 0; i < count; ++i) ASSERT_EQ(runs[i].load(), 1) << "batch " << batch << " task " << i;
  }
}

TEST(RunTasks, NestedBatchesRunOnTheirTask) {
  std::vector<int> sums(4, 0);
  run_tasks(4, [&](int i) {
    std::vector<int> inner(5, 0);
    run_tasks(5, [&](int j) { inner[j] = i * 10 + j; });
    sums[i] = std::accumulate(inner.begin(), inner.end(), 0);
  });
  for (int i = 0; i < 4; ++i) EXPECT_EQ(sums[i], 50 * i + 10);
}

TEST(RunTasks, ConcurrentCallersEachGetTheirTasksDone) {
  std::atomic<long> total{0};
  auto caller = [&] {
    for (int batch = 0; batch < 500; ++batch) run_tasks(3, [&](int i) { total += i + 1; });
  };
  std::thread other(caller);
  caller();
  other.join();
  EXPECT_EQ(total.load(), 2L * 500 * 6);
}

TEST(RunTasks, TheFirstFailureReachesTheCallerAfterEveryTaskEnded) {
  std::atomic<int> ended{0};
  EXPECT_THROW(run_tasks(4,
                         [&](int i) {
                           ++ended;
                           if (i == 2) throw std::runtime_error("task 2");
                         }),
               std::runtime_error);
  EXPECT_EQ(ended.load(), 4);
}

TEST(RunTasks, PartsCoverTheRangeOnce) {
  for (long count : {0L, 1L, 7L, 1000L, 100001L}) {
    for (int parts : {1, 2, 3, 8}) {
      std::vector<std::atomic<int>> hits(count);
      run_in_parts(count, parts, [&](long begin, long end) {
        for (long i = begin; i < end; ++i) ++hits[i];
      });
      for (long i = 0; i < count; ++i) ASSERT_EQ(hits[i].load(), 1) << count << " items, " << parts << " parts";
    }
  }
}

TEST(SortByVertex, GivesStdSortsOrder) {
  std::vector<std::tuple<int, int, int, char>> records;
  unsigned seed = 7;
  for (int i = 0; i < 5000; ++i) {
    seed = seed * 1103515245u + 12345u;
    records.emplace_back(seed % 97, (seed >> 8) % 97, (seed >> 16) % 13, static_cast<char>((seed >> 24) % 2));
  }
  std::vector<std::tuple<int, int, int, char>> expected = records;
  std::sort(expected.begin(), expected.end());
  sort_by_vertex(records, 97);
  EXPECT_EQ(records, expected);
}

// Face states and fold flags are measured in parts from 5,000 triangles and
// summed in order: a mesh that large measures to the bit what its triangles
// measured one by one give.
TEST(RunTasks, FaceStatesInPartsAreTheSerialOnes) {
  const PolygonMesh mesh = test_meshes::uv_sphere(96, 48);
  const Triangulation t = triangulate(mesh.vertices, mesh.faces);
  ASSERT_GE(t.triangles.rows(), 5000);
  std::vector<int> labels(t.triangles.rows());
  for (Eigen::Index f = 0; f < t.triangles.rows(); ++f) labels[f] = static_cast<int>(f % 6);
  const QualityMeasure quality(mesh.vertices, t.triangles, labels);
  Vertices moved = mesh.vertices;
  for (Eigen::Index v = 0; v < moved.rows(); ++v) moved(v, v % 3) += 1e-3 * static_cast<double>(v % 11);
  const FaceStates s = quality.face_states(moved);
  double total = 0.0;
  int flipped = 0;
  FaceStates one = s;
  for (Eigen::Index f = 0; f < t.triangles.rows(); ++f) {
    quality.update_face_state(moved, f, one);
    ASSERT_EQ(one.area[f], s.area[f]);
    ASSERT_EQ(one.deviation_deg[f], s.deviation_deg[f]);
    total += s.area[f];
    flipped += s.flipped[f];
  }
  EXPECT_EQ(s.scale2, total / quality.input_total_area());
  EXPECT_EQ(s.flipped_count, flipped);
}

// The whole run on one thread and on several: the same positions and
// figures to the bit (every sum is taken in order on one thread, every task
// is the one thread's work).
TEST(RunTasks, ADeformationIsTheSameOnAnyNumberOfThreads) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP: one thread only";
#else
  const PolygonMesh mesh = test_meshes::uv_sphere(96, 48, {1.0, 0.8, 0.6});
  const std::vector<int> labels = nearest_labels(mesh);
  const int before = omp_get_max_threads();
  std::vector<DeformResult> results;
  for (int threads : {1, 2, 4}) {
    omp_set_num_threads(threads);
    results.push_back(deform(mesh, labels));
  }
  omp_set_num_threads(before);
  ASSERT_GE(triangulate(mesh.vertices, mesh.faces).triangles.rows(), 5000);
  for (size_t k = 1; k < results.size(); ++k) {
    EXPECT_TRUE(results[k].positions == results[0].positions) << "run " << k;
    EXPECT_EQ(results[k].figures.edge_error, results[0].figures.edge_error);
    EXPECT_EQ(results[k].figures.area_error, results[0].figures.area_error);
    EXPECT_EQ(results[k].iterations, results[0].iterations);
  }
#endif
}

}  // namespace
