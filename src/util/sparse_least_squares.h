#pragma once
// Damped sparse linear least squares, the one solver behind the limit fit and the heights bake:
//
//     x = argmin Σ_s w_s |L_s x − t_s|² + μ |x − x0|²
//
// solved on its normal equations (LᵀWL + μI) x = LᵀWt + μ x0 by Jacobi-preconditioned
// conjugate gradients, from x0. The unknowns are scalars or small vectors (glm::dvec3: the
// three coordinates are one block-diagonal system sharing L). μ is given as a fraction of the
// mean diagonal of LᵀWL, so it means the same whatever the sampling density; unknowns no
// sample touches stay at x0.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace subdfit {

// L in compressed rows: row s has entries [offsets[s], offsets[s + 1]).
struct SparseRows {
    std::vector<std::size_t> offsets{0};
    std::vector<int> column;
    std::vector<double> weight;

    std::size_t rows() const { return offsets.size() - 1; }
    void add(int c, double w) { column.push_back(c), weight.push_back(w); }
    void endRow() { offsets.push_back(column.size()); }
    void append(const SparseRows& rows) {
        for (std::size_t s = 1; s < rows.offsets.size(); ++s) offsets.push_back(column.size() + rows.offsets[s]);
        column.insert(column.end(), rows.column.begin(), rows.column.end());
        weight.insert(weight.end(), rows.weight.begin(), rows.weight.end());
    }

    template <class T>
    T apply(std::size_t row, const std::vector<T>& x) const {
        T sum{};
        for (std::size_t e = offsets[row]; e < offsets[row + 1]; ++e) sum += weight[e] * x[std::size_t(column[e])];
        return sum;
    }
};

namespace detail {
inline double innerProduct(double a, double b) { return a * b; }
template <class V>
double innerProduct(const V& a, const V& b) {
    return double(dot(a, b));  // found by argument-dependent lookup (glm::dot)
}
template <class T>
double innerProduct(const std::vector<T>& a, const std::vector<T>& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += innerProduct(a[i], b[i]);
    return sum;
}
}  // namespace detail

// A square sparse matrix in compressed rows.
struct SparseSquare {
    std::vector<std::size_t> offsets{0};
    std::vector<int> column;
    std::vector<double> value;
};

// LᵀWL over `n` unknowns: for each unknown, the rows it appears in (Lᵀ), each row's entries
// gathered into a dense scratch row. It costs Σ_s |row s|² once, and a product with it its
// entries (the unknowns' neighbours), where a product through L costs twice L's entries.
// L of fewer than 2^32 rows.
SparseSquare normalMatrixOf(const SparseRows& L, const std::vector<double>& rowWeight, std::size_t n);

// Mean entries a row from which the normal matrix is built rather than applied through L: the
// limit fit's stencils (13 entries, 54 samples a vertex) make a matrix of about 40 entries a
// vertex, 35x fewer than L's; the bakes' bilinear rows (4) build one nearly as large as L.
inline constexpr double kNormalMatrixRowEntries = 8.0;

// `rowWeight[s]` = w_s ≥ 0 (0 drops the row). Returns x (x0.size() unknowns).
template <class T>
std::vector<T> solveDampedLeastSquares(const SparseRows& L, const std::vector<T>& targets,
                                       const std::vector<double>& rowWeight, const std::vector<T>& x0,
                                       double dampingFraction, int iterations = 200, double tolerance = 1e-8) {
    const std::size_t n = x0.size();
    std::vector<double> diagonal(n, 0.0);
    for (std::size_t s = 0; s < L.rows(); ++s)
        for (std::size_t e = L.offsets[s]; e < L.offsets[s + 1]; ++e)
            diagonal[std::size_t(L.column[e])] += rowWeight[s] * L.weight[e] * L.weight[e];
    double mean = 0.0;
    for (double d : diagonal) mean += d;
    mean /= double(std::max<std::size_t>(n, 1));
    const double mu = mean > 0.0 ? dampingFraction * mean : 1.0;
    for (double& d : diagonal) d += mu;

    const bool built = L.rows() > 0 && L.rows() <= 0xffffffffu &&
                       double(L.column.size()) >= kNormalMatrixRowEntries * double(L.rows());
    const SparseSquare A = built ? normalMatrixOf(L, rowWeight, n) : SparseSquare{};
    auto normalMatrix = [&](const std::vector<T>& x) {  // (LᵀWL + μI) x
        std::vector<T> out(n);
        for (std::size_t i = 0; i < n; ++i) out[i] = mu * x[i];
        if (built) {
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t e = A.offsets[i]; e < A.offsets[i + 1]; ++e)
                    out[i] += A.value[e] * x[std::size_t(A.column[e])];
            return out;
        }
        for (std::size_t s = 0; s < L.rows(); ++s) {
            if (rowWeight[s] == 0.0) continue;
            const T r = rowWeight[s] * L.apply(s, x);
            for (std::size_t e = L.offsets[s]; e < L.offsets[s + 1]; ++e)
                out[std::size_t(L.column[e])] += L.weight[e] * r;
        }
        return out;
    };
    // The residual b − A x0 with b = LᵀWt + μ x0: the μ terms cancel.
    std::vector<T> r(n, T{});
    for (std::size_t s = 0; s < L.rows(); ++s) {
        if (rowWeight[s] == 0.0) continue;
        const T residual = rowWeight[s] * (targets[s] - L.apply(s, x0));
        for (std::size_t e = L.offsets[s]; e < L.offsets[s + 1]; ++e)
            r[std::size_t(L.column[e])] += L.weight[e] * residual;
    }
    std::vector<T> x = x0, z(n), p;
    for (std::size_t i = 0; i < n; ++i) z[i] = r[i] / diagonal[i];
    p = z;
    double rz = detail::innerProduct(r, z);
    const double stop = tolerance * tolerance * std::max(detail::innerProduct(r, r), 1e-300);
    for (int k = 0; k < iterations && detail::innerProduct(r, r) > stop; ++k) {
        const std::vector<T> Ap = normalMatrix(p);
        const double pAp = detail::innerProduct(p, Ap);
        if (!(pAp > 0.0)) break;
        const double alpha = rz / pAp;
        for (std::size_t i = 0; i < n; ++i) x[i] += alpha * p[i], r[i] -= alpha * Ap[i];
        for (std::size_t i = 0; i < n; ++i) z[i] = r[i] / diagonal[i];
        const double next = detail::innerProduct(r, z);
        for (std::size_t i = 0; i < n; ++i) p[i] = z[i] + (next / rz) * p[i];
        rz = next;
    }
    return x;
}

}  // namespace subdfit
