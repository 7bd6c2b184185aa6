// The projected-Newton minimiser (linear_algebra/minimize_newton.h) and the
// untangling's barrier energy it minimises (deform/barrier_energy.h): the
// energy's derivatives against finite differences, its projected Hessian
// positive semi-definite, and Newton reaching what L-BFGS reaches in far
// fewer iterations.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <optional>
#include <set>

#include "deform/barrier_energy.h"
#include "deform/quality.h"
#include "deform/untangle_flat_charts.h"
#include "io/read_mesh.h"
#include "linear_algebra/minimize_lbfgs.h"
#include "linear_algebra/minimize_newton.h"
#include "mesh/triangulate.h"
#include "nearest_flat_start.h"
#include "test_meshes.h"

namespace polycube {
namespace {

constexpr double kTheta = 0.5;

// Jacobians of every kind the untangling meets: turned over, collapsed,
// sheared, near the identity.
std::vector<Eigen::Matrix2d> jacobians() {
  std::vector<Eigen::Matrix2d> out;
  Eigen::Matrix2d j;
  out.push_back(Eigen::Matrix2d::Identity());
  out.push_back(1.5 * Eigen::Matrix2d::Identity());  // both convex at eps = 0.05
  j << 1.0, 0.1, -0.2, 0.9;
  out.push_back(j);
  j << -0.7, 0.3, 0.2, 0.8;  // turned over
  out.push_back(j);
  j << 1.0, 2.0, 0.5, 1.0;  // collapsed
  out.push_back(j);
  j << 0.05, 1.5, -0.01, 0.3;  // thin
  out.push_back(j);
  for (int i = 0; i < 8; ++i) out.push_back(Eigen::Matrix2d::Random());
  return out;
}

TEST(BarrierEnergy, DerivativesMatchFiniteDifferences) {
  for (const double eps : {0.1, 0.01}) {
    for (const Eigen::Matrix2d& j : jacobians()) {
      Eigen::Matrix2d gradient;
      const Eigen::Matrix4d hessian = barrier_hessian(j, 0.7, eps, kTheta, false);
      barrier_energy(j, 0.7, eps, kTheta, &gradient);
      const double h = 1e-6;
      for (int k = 0; k < 4; ++k) {
        Eigen::Matrix2d plus = j, minus = j;
        plus.data()[k] += h;
        minus.data()[k] -= h;
        const double by_k =
            (barrier_energy(plus, 0.7, eps, kTheta) - barrier_energy(minus, 0.7, eps, kTheta)) / (2 * h);
        EXPECT_NEAR(gradient.data()[k], by_k, 1e-5 * (1.0 + std::abs(by_k)))
            << "det " << j.determinant() << " eps " << eps;
        Eigen::Matrix2d g_plus, g_minus;
        barrier_energy(plus, 0.7, eps, kTheta, &g_plus);
        barrier_energy(minus, 0.7, eps, kTheta, &g_minus);
        const Eigen::Vector4d column =
            Eigen::Map<const Eigen::Vector4d>(Eigen::Matrix2d(g_plus - g_minus).data()) / (2 * h);
        EXPECT_LT((hessian.col(k) - column).norm(), 1e-5 * (1.0 + column.norm()))
            << "det " << j.determinant() << " eps " << eps;
      }
    }
  }
}

// The lanes the untangling runs its triangles in give barrier_energy()'s
// values bit for bit (a rounding changed there changes which triangles end
// collapsed), on every kind of Jacobian and a spread of random ones, lane by
// lane whatever sits in the other lanes.
TEST(BarrierEnergy, LanesGiveTheSameValuesBitForBit) {
  constexpr int kLanes = 8;
  std::vector<Eigen::Matrix2d> all = jacobians();
  for (int i = 0; i < 400; ++i) all.push_back(std::pow(10.0, (i % 7) - 3.0) * Eigen::Matrix2d::Random());
  int compared = 0;
  for (const double eps : {0.1, 0.0123, 1e-12}) {
    for (size_t first = 0; first < all.size(); first += kLanes) {
      double j[4][kLanes], weight[kLanes], value[kLanes], gradient[4][kLanes];
      for (int i = 0; i < kLanes; ++i) {
        const Eigen::Matrix2d& m = all[(first + i) % all.size()];
        for (int k = 0; k < 4; ++k) j[k][i] = m.data()[k];
        weight[i] = 0.25 + 0.1 * i;
      }
      barrier_energy_lanes(j, weight, eps, kTheta, value, gradient);
      for (int i = 0; i < kLanes; ++i) {
        const Eigen::Matrix2d& m = all[(first + i) % all.size()];
        Eigen::Matrix2d expected_gradient;
        const double expected = barrier_energy(m, weight[i], eps, kTheta, &expected_gradient);
        ASSERT_EQ(std::memcmp(&value[i], &expected, sizeof(double)), 0) << value[i] << " against " << expected;
        for (int k = 0; k < 4; ++k)
          ASSERT_EQ(std::memcmp(&gradient[k][i], &expected_gradient.data()[k], sizeof(double)), 0)
              << "entry " << k << ": " << gradient[k][i] << " against " << expected_gradient.data()[k];
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 1200);
}

TEST(BarrierEnergy, ProjectedHessianIsPositiveSemiDefiniteAndExactWhereConvex) {
  int convex = 0, projected = 0;
  for (const Eigen::Matrix2d& j : jacobians()) {
    const Eigen::Matrix4d exact = barrier_hessian(j, 1.0, 0.05, kTheta, false);
    const Eigen::Matrix4d kept = barrier_hessian(j, 1.0, 0.05, kTheta, true);
    const Eigen::Vector4d before = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(exact).eigenvalues();
    const Eigen::Vector4d after = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(kept).eigenvalues();
    EXPECT_GE(after.minCoeff(), -1e-9 * after.cwiseAbs().maxCoeff());
    if (before.minCoeff() > 0.0) {
      ++convex;
      EXPECT_LT((kept - exact).norm(), 1e-12 * exact.norm());
    } else {
      ++projected;
      // Negative curvature turned positive, its size kept (|eigenvalue|).
      EXPECT_NEAR(after.cwiseAbs().sum(), before.cwiseAbs().sum(), 1e-9 * before.cwiseAbs().sum());
    }
  }
  EXPECT_GT(convex, 0);
  EXPECT_GT(projected, 0);
}

// The closed-form projection (the energy's eigensystem through J's singular
// value decomposition) against an iterative eigen-decomposition of the exact
// Hessian, its negative eigenvalues turned to their absolute values: the
// same matrix to rounding, on Jacobians turned over, collapsed, mirrored,
// rotated and of every size, at the untangling's range of eps (where the
// energy is defined: far turned over at a tiny eps, chi underflows).
TEST(BarrierEnergy, ClosedFormProjectionMatchesTheEigenDecomposition) {
  std::vector<Eigen::Matrix2d> all = jacobians();
  Eigen::Matrix2d j;
  j << 0.0, 0.0, 0.0, 0.0;  // every singular value equal (0)
  all.push_back(j);
  j << 0.0, 1.0, 1.0, 0.0;  // a mirror: q = 0
  all.push_back(j);
  j << std::cos(0.3), -std::sin(0.3), std::sin(0.3), std::cos(0.3);  // a rotation: r = 0
  all.push_back(-2.0 * j);
  j << 1.0, 0.0, 0.0, -1e-9;  // all but collapsed, turned over
  all.push_back(j);
  for (int i = 0; i < 300; ++i) all.push_back(std::pow(10.0, (i % 5) - 2.0) * Eigen::Matrix2d::Random());
  int projected = 0;
  for (const double eps : {0.5, 0.05, 1e-4, 1e-9}) {
    for (const Eigen::Matrix2d& m : all) {
      const Eigen::Matrix4d exact = barrier_hessian(m, 0.8, eps, kTheta, false);
      if (!exact.allFinite()) continue;  // chi(det J) below the doubles: no energy to project
      const Eigen::Matrix4d closed = barrier_hessian(m, 0.8, eps, kTheta, true);
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(exact);
      const Eigen::Matrix4d iterative =
          eigen.eigenvectors() * eigen.eigenvalues().cwiseAbs().asDiagonal() * eigen.eigenvectors().transpose();
      if (eigen.eigenvalues().minCoeff() < 0.0) ++projected;
      EXPECT_LT((closed - iterative).norm(), 1e-9 * iterative.norm())
          << "J " << m.reshaped().transpose() << " eps " << eps << "\n"
          << closed << "\n"
          << iterative;
    }
  }
  EXPECT_GT(projected, 400);
}

// Rosenbrock's valley as one element of two unknowns, its Hessian projected
// as the untangling's are: Newton needs a tenth of L-BFGS's iterations.
TEST(MinimizeNewton, FindsTheRosenbrockMinimumInFewIterations) {
  const ElementObjective rosenbrock = [](const Eigen::VectorXd& x, Eigen::VectorXd* g, const HessianSink* h) {
    const double a = 1.0 - x[0], b = x[1] - x[0] * x[0];
    if (g) {
      g->resize(2);
      (*g)[0] = -2.0 * a - 400.0 * x[0] * b;
      (*g)[1] = 200.0 * b;
    }
    if (h) {
      Eigen::Matrix2d m;
      m << 2.0 - 400.0 * b + 800.0 * x[0] * x[0], -400.0 * x[0], -400.0 * x[0], 200.0;
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(m);
      m = eigen.eigenvectors() * eigen.eigenvalues().cwiseAbs().asDiagonal() * eigen.eigenvectors().transpose();
      (*h)(0, 1, m.data());
    }
    return a * a + 100.0 * b * b;
  };
  Eigen::VectorXd x(2);
  x << -1.2, 1.0;
  NewtonMinimizer newton;
  const NewtonResult r = newton.minimize(rosenbrock, {0, 1}, 2, 2, x, 200, 1e-10, 0.0);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(x[0], 1.0, 1e-6);
  EXPECT_NEAR(x[1], 1.0, 1e-6);
  EXPECT_LT(r.iterations, 30);
  EXPECT_EQ(r.factorizations, r.iterations);
}

// Held unknowns stay; a shared unknown (two corners of one element on the
// same entry) sums its blocks: a chain of springs, each element a quadratic
// (x_i - x_j - 1)^2 in two unknowns, solved exactly by one Newton step.
// Springs x_a - x_b = rest on a chain, each vertex also tied to the held
// one (its first) at its distance along the chain, so the system is well
// conditioned at every size: the minimum (every spring at rest) in one
// step, also past SparseCholesky's threshold (60,000 unknowns: CHOLMOD
// where its plugin loads).
TEST(MinimizeNewton, SolvesAQuadraticInOneStepAndHoldsTheRest) {
  for (const int n : {50, 60'000}) {
    // Per element: its two unknowns; rests alongside. Vertex i of the chain
    // is unknown n - 1 - i: the held one is the vector's tail.
    std::vector<int> elements;
    std::vector<double> rests;
    for (int i = 0; i + 1 < n; ++i) {
      elements.insert(elements.end(), {n - 2 - i, n - 1 - i});
      rests.push_back(1.0);
      if (i > 0) elements.insert(elements.end(), {n - 1 - i, n - 1}), rests.push_back(i);
    }
    elements.push_back(3), elements.push_back(3), rests.push_back(0.0);  // on one unknown twice: zero energy
    // Handed over one element at a time, the smallest blocks there are.
    const ElementObjective springs = [&](const Eigen::VectorXd& x, Eigen::VectorXd* g, const HessianSink* h) {
      double f = 0.0;
      if (g) g->setZero(x.size());
      for (size_t e = 0; e < rests.size(); ++e) {
        const int a = elements[2 * e], b = elements[2 * e + 1];
        const double r = a == b ? 0.0 : x[a] - x[b] - rests[e];
        f += r * r;
        if (g && a != b) (*g)[a] += 2.0 * r, (*g)[b] -= 2.0 * r;
        if (h) {
          const double s = a == b ? 0.0 : 2.0;
          const double block[4] = {s, -s, -s, s};
          (*h)(e, 1, block);
        }
      }
      return f;
    };
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    x[n - 1] = 5.0;  // the chain's first vertex, held
    NewtonMinimizer newton;
    const NewtonResult r = newton.minimize(springs, elements, 2, n - 1, x, 10, 1e-9, 0.0);
    EXPECT_TRUE(r.converged) << n;
    EXPECT_LE(r.iterations, 2) << n;
    EXPECT_EQ(x[n - 1], 5.0);
    double error = 0.0;
    for (int i = 1; i < n; ++i) error = std::max(error, std::abs(x[n - 1 - i] - (5.0 + i)));
    EXPECT_LT(error, 1e-9) << n;
  }
}

// Hessians handed over in blocks of any size build the same system as all at
// once: the same steps bit for bit. A chain of nonlinear springs, each
// element (x_a - x_b - 1)^4 + (x_a - x_b)^2 / 10 in two unknowns, several
// Newton steps from a stretched start, the last unknown held.
TEST(MinimizeNewton, HessiansInBlocksGiveTheSameStepsBitForBit) {
  const int n = 500;
  std::vector<int> elements;
  for (int i = 0; i + 1 < n; ++i) elements.insert(elements.end(), {i, i + 1});
  const size_t count = elements.size() / 2;
  // Its Hessians handed over `block` elements at a time.
  auto springs = [&](size_t block) -> ElementObjective {
    return [&, block](const Eigen::VectorXd& x, Eigen::VectorXd* g, const HessianSink* h) {
      double f = 0.0;
      if (g) g->setZero(x.size());
      std::vector<double> hessians;
      for (size_t e = 0; e < count; ++e) {
        const int a = elements[2 * e], b = elements[2 * e + 1];
        const double d = x[a] - x[b], r = d - 1.0;
        f += r * r * r * r + 0.1 * d * d;
        const double slope = 4.0 * r * r * r + 0.2 * d, curvature = 12.0 * r * r + 0.2;
        if (g) (*g)[a] += slope, (*g)[b] -= slope;
        if (!h) continue;
        hessians.insert(hessians.end(), {curvature, -curvature, -curvature, curvature});
        if (hessians.size() == 4 * block || e + 1 == count) {
          (*h)(e + 1 - hessians.size() / 4, hessians.size() / 4, hessians.data());
          hessians.clear();
        }
      }
      return f;
    };
  };
  std::vector<Eigen::VectorXd> results;
  std::vector<int> iterations;
  for (const size_t block : {count, size_t{1}, size_t{7}}) {
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, 0.0, 0.5 * n);
    NewtonMinimizer newton;
    const NewtonResult r = newton.minimize(springs(block), elements, 2, n - 1, x, 20, 1e-12, 0.0);
    EXPECT_GT(r.iterations, 3) << block;
    results.push_back(x);
    iterations.push_back(r.iterations);
  }
  for (size_t k = 1; k < results.size(); ++k) {
    EXPECT_EQ(iterations[k], iterations[0]);
    EXPECT_TRUE(results[k] == results[0]) << "blocks of another size moved the result by "
                                          << (results[k] - results[0]).lpNorm<Eigen::Infinity>();
  }
}

// A real untangling: fandisk's flat charts from its nearest-axis labels (the
// first flat solve, with turned-over triangles).
struct FandiskFlat {
  PolygonMesh mesh;
  Triangulation t;
  std::vector<int> labels;
  FlatCharts flat;
};

std::optional<FandiskFlat> fandisk_flat() {
  const std::string path = std::string(POLYCUBE_MESH_DATA) + "/fandisk.off";
  if (!std::ifstream(path).good()) return std::nullopt;
  FandiskFlat f;
  f.mesh = read_mesh(path);
  f.t = triangulate(f.mesh.vertices, f.mesh.faces);
  f.labels = test_meshes::nearest_triangle_labels(f.mesh, f.t);
  f.flat =
      test_meshes::flatten_from_input(f.mesh, f.t, f.labels, QualityMeasure(f.mesh.vertices, f.t.triangles, f.labels));
  return f;
}

// Untangled by each minimiser.
TEST(UntangleFlatCharts, NewtonAndLbfgsOpenTheSameTriangles) {
  const std::optional<FandiskFlat> f = fandisk_flat();
  if (!f) GTEST_SKIP() << "fandisk.off is missing: run `make data`";
  const PolygonMesh& mesh = f->mesh;
  const Triangulation& t = f->t;
  const std::vector<int>& labels = f->labels;
  const FlatCharts& flat = f->flat;
  const QualityMeasure quality(mesh.vertices, t.triangles, labels);
  ASSERT_GT(flat.first_positions.rows(), 0);
  const FaceStates tangled = quality.face_states(flat.first_positions);
  ASSERT_GT(tangled.flipped_count, 0);

  std::vector<Figures> figures;
  std::vector<UntangledCharts> runs;
  for (const UntangleMinimiser m : {UntangleMinimiser::lbfgs, UntangleMinimiser::newton}) {
    runs.push_back(untangle_flat_charts(mesh.vertices, flat.first_positions, t.triangles, labels, kUntangleRounds,
                                        kUntangleLocalShare, {}, m));
    figures.push_back(quality.measure(runs.back().positions));
  }
  const UntangledCharts &lbfgs = runs[0], &newton = runs[1];
  for (const Figures& f : figures) {
    EXPECT_EQ(f.flipped_faces, 0);
    EXPECT_LT(f.normal_deviation_max_deg, 1e-6);
  }
  EXPECT_TRUE(lbfgs.untangled);
  EXPECT_TRUE(newton.untangled);
  EXPECT_EQ(lbfgs.factorizations, 0);
  EXPECT_GT(newton.factorizations, 0);
  // A tenth of the iterations, each a factorisation where L-BFGS's is a
  // gradient, to figures as good.
  EXPECT_LT(10 * newton.iterations, lbfgs.iterations);
  EXPECT_LE(figures[1].collapsed_faces, figures[0].collapsed_faces + 2);
  EXPECT_LT(figures[1].area_error, figures[0].area_error + 0.005);
  EXPECT_LT(figures[1].edge_error, figures[0].edge_error + 0.005);
}

// The caller's stop is answered within one Newton iteration (a
// factorisation), not when the untangling ends: what a user's Esc waits for
// at a million triangles, where one untangling takes minutes.
TEST(UntangleFlatCharts, StopsWithinOneNewtonIteration) {
  const std::optional<FandiskFlat> f = fandisk_flat();
  if (!f) GTEST_SKIP() << "fandisk.off is missing: run `make data`";
  auto untangle = [&f](const std::function<bool()>& stop) {
    return untangle_flat_charts(f->mesh.vertices, f->flat.first_positions, f->t.triangles, f->labels, kUntangleRounds,
                                kUntangleLocalShare, {}, UntangleMinimiser::newton, stop);
  };
  int polls = 0;
  const UntangledCharts whole = untangle([&polls] { return ++polls < 0; });
  ASSERT_TRUE(whole.untangled);
  EXPECT_FALSE(whole.stopped);
  ASSERT_GT(whole.factorizations, 4);
  EXPECT_GE(polls, whole.iterations + whole.rounds);  // before every round and every iteration
  int asked = 0;
  const UntangledCharts stopped = untangle([&asked] { return ++asked >= 3; });
  EXPECT_EQ(asked, 3);  // no question after the first true
  EXPECT_TRUE(stopped.stopped);
  EXPECT_TRUE(stopped.refused);
  EXPECT_FALSE(stopped.untangled);
  EXPECT_LE(stopped.factorizations, 2);
  EXPECT_EQ(stopped.rounds, 1);
}

}  // namespace
}  // namespace polycube
