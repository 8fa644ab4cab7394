#include "util/sparse_least_squares.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <random>

namespace subdfit {
namespace {

// Random rows of `entries` distinct columns each over `n` unknowns, weights in [0.1, 1).
SparseRows randomRows(int rows, int entries, int n, std::mt19937& random) {
    SparseRows L;
    std::uniform_real_distribution<double> weight(0.1, 1.0);
    for (int s = 0; s < rows; ++s) {
        const int start = int(random() % unsigned(n));
        for (int k = 0; k < entries; ++k) L.add((start + 3 * k) % n, weight(random));
        L.endRow();
    }
    return L;
}

// (LᵀWL + μI) x = LᵀWt + μ x0 solved densely by Gaussian elimination, μ as the solver makes it.
std::vector<double> denseSolution(const SparseRows& L, const std::vector<double>& t, const std::vector<double>& w,
                                  const std::vector<double>& x0, double dampingFraction) {
    const size_t n = x0.size();
    std::vector<std::vector<double>> A(n, std::vector<double>(n + 1, 0.0));
    double mean = 0.0;
    for (size_t s = 0; s < L.rows(); ++s)
        for (size_t e = L.offsets[s]; e < L.offsets[s + 1]; ++e) {
            mean += w[s] * L.weight[e] * L.weight[e];
            A[size_t(L.column[e])][n] += w[s] * L.weight[e] * t[s];
            for (size_t f = L.offsets[s]; f < L.offsets[s + 1]; ++f)
                A[size_t(L.column[e])][size_t(L.column[f])] += w[s] * L.weight[e] * L.weight[f];
        }
    const double mu = dampingFraction * mean / double(n);
    for (size_t i = 0; i < n; ++i) A[i][i] += mu, A[i][n] += mu * x0[i];
    for (size_t i = 0; i < n; ++i)
        for (size_t r = i + 1; r < n; ++r) {
            const double f = A[r][i] / A[i][i];
            for (size_t c = i; c <= n; ++c) A[r][c] -= f * A[i][c];
        }
    std::vector<double> x(n);
    for (size_t i = n; i-- > 0;) {
        double sum = A[i][n];
        for (size_t c = i + 1; c < n; ++c) sum -= A[i][c] * x[c];
        x[i] = sum / A[i][i];
    }
    return x;
}

// Long rows (the limit fit's stencils) take the built normal matrix, short ones (the bakes')
// the product through L: both reach the dense solution, with rows weighted 0 dropped.
TEST(SparseLeastSquares, LongAndShortRowsReachTheDenseSolution) {
    std::mt19937 random(7);
    for (const int entries : {4, 13}) {
        constexpr int n = 60, rows = 400;
        const SparseRows L = randomRows(rows, entries, n, random);
        ASSERT_EQ(double(L.column.size()) >= kNormalMatrixRowEntries * rows, entries == 13);
        std::normal_distribution<double> value;
        std::vector<double> t(rows), w(rows), x0(n);
        for (int s = 0; s < rows; ++s) t[size_t(s)] = value(random), w[size_t(s)] = s % 7 == 0 ? 0.0 : 1.0;
        for (double& x : x0) x = value(random);
        const std::vector<double> solved = solveDampedLeastSquares(L, t, w, x0, 0.02, 500, 1e-12);
        const std::vector<double> expected = denseSolution(L, t, w, x0, 0.02);
        for (int i = 0; i < n; ++i) EXPECT_NEAR(solved[size_t(i)], expected[size_t(i)], 1e-8) << entries << " " << i;
    }
}

// The built matrix is LᵀWL, entry for entry, and keeps no entry for unknowns no weighted row joins.
TEST(SparseLeastSquares, TheNormalMatrixIsLTransposeWL) {
    std::mt19937 random(3);
    const SparseRows L = randomRows(50, 9, 40, random);
    std::vector<double> w(50);
    for (size_t s = 0; s < w.size(); ++s) w[s] = 0.5 + double(s % 3);
    const SparseSquare A = normalMatrixOf(L, w, 40);
    ASSERT_EQ(A.offsets.size(), 41u);
    for (size_t i = 0; i < 40; ++i)
        for (size_t k = A.offsets[i]; k < A.offsets[i + 1]; ++k) {
            if (k > A.offsets[i]) EXPECT_LT(A.column[k - 1], A.column[k]);
            double expected = 0.0;
            for (size_t s = 0; s < L.rows(); ++s) {
                double li = 0.0, lj = 0.0;
                for (size_t e = L.offsets[s]; e < L.offsets[s + 1]; ++e) {
                    if (size_t(L.column[e]) == i) li += L.weight[e];
                    if (L.column[e] == A.column[k]) lj += L.weight[e];
                }
                expected += w[s] * li * lj;
            }
            EXPECT_NEAR(A.value[k], expected, 1e-12);
        }
}

// Vector unknowns (the limit fit's dvec3) solve as three systems sharing L.
TEST(SparseLeastSquares, VectorUnknownsSolveEachCoordinate) {
    std::mt19937 random(11);
    constexpr int n = 30, rows = 200;
    const SparseRows L = randomRows(rows, 13, n, random);
    std::normal_distribution<double> value;
    std::vector<glm::dvec3> t(rows), x0(n);
    for (auto& v : t) v = {value(random), value(random), value(random)};
    const std::vector<double> w(rows, 1.0);
    const std::vector<glm::dvec3> solved = solveDampedLeastSquares(L, t, w, x0, 0.02, 500, 1e-12);
    for (int c = 0; c < 3; ++c) {
        std::vector<double> tc(rows), x0c(n, 0.0);
        for (int s = 0; s < rows; ++s) tc[size_t(s)] = t[size_t(s)][c];
        const std::vector<double> expected = denseSolution(L, tc, w, x0c, 0.02);
        for (int i = 0; i < n; ++i) EXPECT_NEAR(solved[size_t(i)][c], expected[size_t(i)], 1e-8);
    }
}

}  // namespace
}  // namespace subdfit
