#include <dlfcn.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "linear_algebra/laplacian.h"
#include "linear_algebra/sparse_cholesky.h"
#include "linear_algebra/supernodal_factor.h"
#include "mesh/triangulate.h"
#include "mesh/union_find.h"
#include "test_meshes.h"

namespace {

using namespace polycube;

SparseMatrix shifted_laplacian(const PolygonMesh& mesh) {
  const Triangles t = triangulate(mesh.vertices, mesh.faces).triangles;
  Laplacian laplacian(static_cast<int>(mesh.vertices.rows()), t);
  laplacian.assemble(cotangent_weights(mesh.vertices, t), 1e-6);
  return laplacian.matrix();
}

double relative_residual(const SparseMatrix& a, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& b) {
  return (a * x - b).norm() / b.norm();
}

#ifdef POLYCUBE_WITH_CHOLMOD
// The plugin is built beside this program (CMakeLists.txt): it must load,
// or large systems would silently take the slow factorisation.
TEST(SparseCholesky, TheCholmodPluginLoads) {
  EXPECT_TRUE(supernodal_available());
  EXPECT_NE(make_supernodal_factor(), nullptr);
}

// The plugin's OpenBLAS runs on one thread unless the environment asks for
// more (supernodal_factor.cpp): its waiting threads spin on a shared machine.
TEST(SparseCholesky, ThePluginsOpenBlasRunsOnOneThread) {
  for (const char* variable : {"OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS"})
    if (std::getenv(variable)) GTEST_SKIP() << variable << " is set";
  ASSERT_TRUE(supernodal_available());
  // Loaded by the plugin, so RTLD_NOLOAD finds it without loading another.
  void* blas = dlopen("libopenblas.so.0", RTLD_NOW | RTLD_NOLOAD);
  if (!blas) GTEST_SKIP() << "the plugin's BLAS is not OpenBLAS";
  using GetThreads = int (*)();
  const auto get_threads = reinterpret_cast<GetThreads>(dlsym(blas, "openblas_get_num_threads"));
  ASSERT_NE(get_threads, nullptr);
  EXPECT_EQ(get_threads(), 1);
  dlclose(blas);
}

long voluntary_context_switches() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_nvcsw;
}

// CHOLMOD's own OpenMP teams (four threads per large supernode, fixed in
// Debian's build) run on the calling thread (supernodal_cholmod.cpp): with
// them a factorisation of this size waited on futexes thousands of times.
TEST(SparseCholesky, CholmodsFactorisationWakesNoThreads) {
  const SparseMatrix a = shifted_laplacian(test_meshes::uv_sphere(400, 150));
  SparseCholesky cholesky;
  cholesky.analyze(a);
  cholesky.factorize(a);  // threads that start with the first call, started
  ASSERT_STREQ(cholesky.backend(), "cholmod-supernodal");
  const long before = voluntary_context_switches();
  for (int i = 0; i < 3; ++i) cholesky.factorize(a);
  const Eigen::MatrixX3d b = Eigen::MatrixX3d::Ones(a.rows(), 3);
  const Eigen::MatrixX3d x = cholesky.solve(b);
  EXPECT_LT(voluntary_context_switches() - before, 30);
  EXPECT_TRUE(x.allFinite());
}
#endif

#ifdef _OPENMP
// The flat charts' three systems are factorised on threads of their own at
// once (chart_planes.cpp): each factor the same bit for bit as alone, and
// the plugin's switch of OpenMP's nesting (supernodal_cholmod.cpp), a
// setting of each thread's own, back as it was.
TEST(SparseCholesky, CholmodFactorisesOnSeveralThreadsAtOnce) {
  const SparseMatrix a = shifted_laplacian(test_meshes::uv_sphere(400, 150));
  const Eigen::MatrixX3d b = Eigen::MatrixX3d::Random(a.rows(), 3);
  SparseCholesky alone;
  alone.analyze(a);
  alone.factorize(a);
  ASSERT_STREQ(alone.backend(), "cholmod-supernodal");
  const Eigen::MatrixX3d expected = alone.solve(b);
  const int levels = omp_get_max_active_levels();
  std::vector<Eigen::MatrixX3d> solutions(2);
  std::vector<std::thread> threads;
  for (Eigen::MatrixX3d& solution : solutions)
    threads.emplace_back([&] {
      SparseCholesky cholesky;
      cholesky.analyze(a);
      for (int i = 0; i < 4; ++i) {
        cholesky.factorize(a);
        solution = cholesky.solve(b);
      }
    });
  for (std::thread& thread : threads) thread.join();
  for (const Eigen::MatrixX3d& solution : solutions) EXPECT_EQ(solution, expected);
  EXPECT_EQ(omp_get_max_active_levels(), levels);
}
#endif

TEST(SparseCholesky, SmallAndLargeSystemsSolveAccurately) {
  for (const auto& [mesh, expected] : {std::pair{test_meshes::uv_sphere(32, 16), "eigen-simplicial"},
                                       std::pair{test_meshes::uv_sphere(400, 150), "cholmod-supernodal"}}) {
    const SparseMatrix a = shifted_laplacian(mesh);
    SparseCholesky cholesky;
    cholesky.analyze(a);
    cholesky.factorize(a);
    const Eigen::MatrixX3d b = Eigen::MatrixX3d::Random(a.rows(), 3);
    EXPECT_LT(relative_residual(a, cholesky.solve(b), b), 1e-8) << cholesky.backend();
#ifdef POLYCUBE_WITH_CHOLMOD
    EXPECT_STREQ(cholesky.backend(), expected);
#endif
    // Refactorising with new values of the same pattern.
    const SparseMatrix twice = 2.0 * a;
    cholesky.factorize(twice);
    EXPECT_LT(relative_residual(twice, cholesky.solve(b), b), 1e-8);
    EXPECT_EQ(cholesky.factorizations(), 2);
  }
}

// A kept ordering gives the same factor bit for bit, and survives release();
// one of another size is ignored (the analysis computes its own). For
// CHOLMOD's systems too: its ordering is handed back to it (CHOLMOD_GIVEN).
TEST(SparseCholesky, AKeptOrderingGivesTheSameSolutionBitForBit) {
  for (const PolygonMesh& mesh : {test_meshes::uv_sphere(48, 24), test_meshes::uv_sphere(400, 150)}) {
    const SparseMatrix a = shifted_laplacian(mesh);
    const Eigen::MatrixX3d b = Eigen::MatrixX3d::Random(a.rows(), 3);
    SparseCholesky first;
    first.analyze(a);
    first.factorize(a);
    const Eigen::MatrixX3d expected = first.solve(b);
    ASSERT_EQ(first.ordering().size(), a.rows()) << first.backend();
    first.release();
    EXPECT_TRUE(first.released());
    ASSERT_EQ(first.ordering().size(), a.rows());
    SparseCholesky second;
    second.analyze(a, first.ordering());
    second.factorize(a);
    EXPECT_STREQ(second.backend(), first.backend());
    EXPECT_FALSE(second.released());
    EXPECT_EQ(second.solve(b), expected) << second.backend();
    EXPECT_EQ(second.ordering().indices(), first.ordering().indices());
    // A natural ordering (another fill) still solves, not bit for bit.
    SparseCholesky::Ordering identity(a.rows());
    identity.setIdentity();
    SparseCholesky natural;
    natural.analyze(a, identity);
    natural.factorize(a);
    EXPECT_LT(relative_residual(a, natural.solve(b), b), 1e-8);
    SparseCholesky::Ordering wrong_size(3);
    wrong_size.setIdentity();
    natural.analyze(a, wrong_size);
    natural.factorize(a);
    EXPECT_EQ(natural.solve(b), expected);
    // Two columns in one pass, as each alone.
    const Eigen::MatrixX2d two = second.solve(Eigen::MatrixX2d(b.leftCols(2)));
    EXPECT_LT((two - expected.leftCols(2)).norm(), 1e-12 * expected.norm());
  }
}

// The analysis orders the full symmetric pattern directly: the same ordering
// as Eigen's own analysis, so the same factor bit for bit.
TEST(SparseCholesky, OrdersAsEigensOwnAnalysis) {
  for (const PolygonMesh& mesh : {test_meshes::uv_sphere(48, 24), test_meshes::uv_sphere(7, 5)}) {
    const SparseMatrix a = shifted_laplacian(mesh);
    SparseCholesky ours;
    ours.analyze(a);
    Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> eigen;
    eigen.analyzePattern(a);
    EXPECT_EQ(ours.ordering().indices(), eigen.permutationPinv().indices());
    ours.factorize(a);
    eigen.factorize(a);
    const Eigen::MatrixX3d b = Eigen::MatrixX3d::Random(a.rows(), 3);
    EXPECT_EQ(ours.solve(b), Eigen::MatrixX3d(eigen.solve(b)));
  }
}

// Several right-hand sides are solved in one pass over the factor: each
// column to the very bits Eigen's solve of it alone gives, zero entries
// (which Eigen's triangular solve skips) and negative zeros included.
TEST(SparseCholesky, ColumnsSolvedTogetherAreTheColumnsSolvedAlone) {
  const SparseMatrix a = shifted_laplacian(test_meshes::uv_sphere(48, 24));
  SparseCholesky ours;
  ours.analyze(a);
  ours.factorize(a);
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> eigen;
  eigen.compute(a);
  std::srand(3);
  Eigen::MatrixX3d b = Eigen::MatrixX3d::Random(a.rows(), 3);
  for (Eigen::Index i = 0; i < b.rows(); i += 3) b(i, 1) = 0.0;  // sparse columns, differently so
  for (Eigen::Index i = 0; i < b.rows(); i += 5) b(i, 2) = -0.0;
  b.col(0).head(b.rows() / 2).setZero();
  const Eigen::MatrixX3d three = ours.solve(b);
  const Eigen::MatrixX2d two = ours.solve(Eigen::MatrixX2d(b.leftCols(2)));
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd alone = eigen.solve(Eigen::VectorXd(b.col(c)));
    for (Eigen::Index i = 0; i < b.rows(); ++i) {
      EXPECT_EQ(std::signbit(three(i, c)), std::signbit(alone[i]));
      ASSERT_EQ(three(i, c), alone[i]) << c << " " << i;
      if (c < 2) {
        ASSERT_EQ(two(i, c), alone[i]) << c << " " << i;
      }
    }
  }
  EXPECT_EQ(ours.solve(Eigen::VectorXd(b.col(1))), three.col(1));
}

// A matrix renumbered in the elimination order an analysis chose, analysed
// as it is (analyze_in_order), solves as the matrix did, on either backend:
// to the bit with CHOLMOD, whose factor is then the same one.
TEST(SparseCholesky, AMatrixInItsEliminationOrderSolvesAsBefore) {
  for (const PolygonMesh& mesh : {test_meshes::uv_sphere(32, 16), test_meshes::uv_sphere(400, 150)}) {
    const SparseMatrix a = shifted_laplacian(mesh);
    SparseCholesky first;
    first.analyze(a);
    first.factorize(a);
    // Unknown i at place[i]: the place its elimination takes.
    const Eigen::VectorXi& eliminated = first.ordering().indices();
    Eigen::VectorXi place(a.rows());
    for (int k = 0; k < a.rows(); ++k) place[eliminated[k]] = k;
    const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> to_place(place);
    const SparseMatrix in_order = to_place * a * to_place.transpose();
    SparseCholesky second;
    second.analyze_in_order(in_order);
    second.factorize(in_order);
    EXPECT_STREQ(second.backend(), first.backend());
    const Eigen::VectorXd b = Eigen::VectorXd::Random(a.rows());
    const Eigen::VectorXd x = to_place.transpose() * second.solve(Eigen::VectorXd(to_place * b));
    EXPECT_LT((a * x - b).norm() / b.norm(), 1e-8) << second.backend();
    if (std::string(first.backend()) == "cholmod-supernodal") EXPECT_TRUE(x == first.solve(b));
  }
}

// A copy of CHOLMOD's analysis, factorised, is the factor the analysis
// itself gives, bit for bit (the flat charts' systems at scale,
// chart_planes.h); there is none of Eigen's LDLT, nor once factorised.
TEST(SparseCholesky, ACopiedAnalysisFactorisesBitForBit) {
  for (const PolygonMesh& mesh : {test_meshes::uv_sphere(32, 16), test_meshes::uv_sphere(400, 150)}) {
    const SparseMatrix a = shifted_laplacian(mesh);
    SparseCholesky analysed;
    analysed.analyze(a);
    std::unique_ptr<SparseCholesky> copy = analysed.copy_analysis();
    analysed.factorize(a);
    const Eigen::MatrixX3d b = Eigen::MatrixX3d::Random(a.rows(), 3);
    if (std::string(analysed.backend()) != "cholmod-supernodal") {
      EXPECT_EQ(copy, nullptr);
      continue;
    }
    ASSERT_NE(copy, nullptr);
    EXPECT_EQ(analysed.copy_analysis(), nullptr);                    // factorised: nothing to copy
    std::unique_ptr<SparseCholesky> second = copy->copy_analysis();  // a copy's copy
    ASSERT_NE(second, nullptr);
    for (SparseCholesky* factor : {copy.get(), second.get()}) {
      factor->factorize(a);
      EXPECT_STREQ(factor->backend(), "cholmod-supernodal");
      EXPECT_EQ(factor->ordering().indices(), analysed.ordering().indices());
      EXPECT_EQ(factor->solve(b), analysed.solve(b));
    }
  }
}

// Unknowns held equal on CHOLMOD's factor of the system without the joins
// (SparseCholesky::hold_equal) minimise what the joined system's own
// factor does, to rounding; Eigen's LDLT and a Y over its budget decline.
TEST(SparseCholesky, HeldEqualUnknownsSolveAsTheirJoinedSystem) {
  const SparseMatrix small = shifted_laplacian(test_meshes::uv_sphere(32, 16));
  SparseCholesky simplicial;
  simplicial.analyze(small);
  simplicial.factorize(small);
  EXPECT_EQ(simplicial.hold_equal({{0, 1}}, 1'000'000), nullptr);
  const SparseMatrix a = shifted_laplacian(test_meshes::uv_sphere(400, 150));
  const int n = static_cast<int>(a.rows());
  SparseCholesky cholesky;
  cholesky.analyze(a);
  cholesky.factorize(a);
  if (std::string(cholesky.backend()) != "cholmod-supernodal") GTEST_SKIP() << "no CHOLMOD plugin";
  // Chains and stars of joins, near and far apart (every join independent).
  std::vector<std::pair<int, int>> joins;
  for (int i = 0; i < 60; ++i) joins.emplace_back((i * 7919) % n, (i * 104729 + 13) % n);
  for (int i = 0; i < 5; ++i) joins.emplace_back(1000, 1001 + i);
  UnionFind sets(n);
  std::vector<std::pair<int, int>> independent;
  for (const auto& [p, q] : joins)
    if (sets.join(p, q)) independent.emplace_back(p, q);
  EXPECT_EQ(cholesky.hold_equal(independent, 10), nullptr);
  // So many that their Schur complement costs more than a factorisation.
  std::vector<std::pair<int, int>> many;
  for (int i = 0; i < 1500; ++i) many.emplace_back(i, i + n / 2);
  EXPECT_EQ(cholesky.hold_equal(many, std::numeric_limits<long>::max()), nullptr);
  const std::shared_ptr<const SparseCholesky::Joins> held = cholesky.hold_equal(independent, 100L * n);
  ASSERT_NE(held, nullptr);
  // The joined system P^T A P, factorised on its own.
  std::vector<int> unknown(n), of_root(n, -1);
  int m = 0;
  for (int v = 0; v < n; ++v) {
    int& u = of_root[sets.root(v)];
    if (u < 0) u = m++;
    unknown[v] = u;
  }
  std::vector<Eigen::Triplet<double>> entries;
  for (int c = 0; c < n; ++c)
    for (SparseMatrix::InnerIterator it(a, c); it; ++it)
      entries.emplace_back(unknown[it.row()], unknown[c], it.value());
  SparseMatrix joined(m, m);
  joined.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<SparseMatrix> direct(joined);
  ASSERT_EQ(direct.info(), Eigen::Success);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 2);
  Eigen::MatrixXd reduced_b = Eigen::MatrixXd::Zero(m, 2);
  for (int v = 0; v < n; ++v) reduced_b.row(unknown[v]) += b.row(v);
  const Eigen::MatrixXd expected = direct.solve(reduced_b);
  const Eigen::MatrixXd x = cholesky.solve(b, *held);
  double worst = 0.0;
  for (int v = 0; v < n; ++v) worst = std::max(worst, (x.row(v) - expected.row(unknown[v])).cwiseAbs().maxCoeff());
  EXPECT_LT(worst, 1e-9 * expected.cwiseAbs().maxCoeff());
  // Without the joins it would differ far more than that.
  EXPECT_GT((cholesky.solve(Eigen::MatrixX2d(b)) - x).cwiseAbs().maxCoeff(), 1e-3 * expected.cwiseAbs().maxCoeff());
}

TEST(SparseCholesky, IndefiniteLargeSystemFallsBackToLdlt) {
  SparseMatrix a = shifted_laplacian(test_meshes::uv_sphere(400, 150));
  SparseCholesky cholesky;
  cholesky.analyze(a);
  a.coeffRef(0, 0) = -1.0;  // one negative pivot: not positive definite
  // Silently: CHOLMOD's warning would land in the program's JSON on stdout.
  ::testing::internal::CaptureStdout();
  cholesky.factorize(a);
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_STREQ(cholesky.backend(), "eigen-simplicial");
  const Eigen::MatrixX3d b = Eigen::MatrixX3d::Random(a.rows(), 3);
  EXPECT_LT(relative_residual(a, cholesky.solve(b), b), 1e-6);
}

}  // namespace
