#include "util/sparse_least_squares.h"

#include <cstdint>

namespace subdfit {

SparseSquare normalMatrixOf(const SparseRows& L, const std::vector<double>& rowWeight, std::size_t n) {
    // Lᵀ: each unknown's entries (row, weight), in row order.
    std::vector<std::size_t> first(n + 1, 0);
    for (const int c : L.column) ++first[std::size_t(c) + 1];
    for (std::size_t i = 0; i < n; ++i) first[i + 1] += first[i];
    std::vector<std::size_t> fill(first.begin(), first.end() - 1);
    std::vector<std::uint32_t> rowOf(L.column.size());  // the limit fit's rows number a few million
    std::vector<double> weightOf(L.column.size());
    for (std::size_t s = 0; s < L.rows(); ++s)
        for (std::size_t e = L.offsets[s]; e < L.offsets[s + 1]; ++e) {
            const std::size_t at = fill[std::size_t(L.column[e])]++;
            rowOf[at] = std::uint32_t(s);
            weightOf[at] = L.weight[e];
        }
    SparseSquare A;
    A.offsets.reserve(n + 1);
    std::vector<double> dense(n, 0.0);
    std::vector<char> touched(n, 0);
    std::vector<int> columns;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = first[i]; k < first[i + 1]; ++k) {
            const std::size_t s = rowOf[k];
            if (rowWeight[s] == 0.0) continue;
            const double f = rowWeight[s] * weightOf[k];
            for (std::size_t e = L.offsets[s]; e < L.offsets[s + 1]; ++e) {
                const int j = L.column[e];
                if (!touched[std::size_t(j)]) touched[std::size_t(j)] = 1, columns.push_back(j);
                dense[std::size_t(j)] += f * L.weight[e];
            }
        }
        std::sort(columns.begin(), columns.end());
        for (const int j : columns) {
            A.column.push_back(j);
            A.value.push_back(dense[std::size_t(j)]);
            dense[std::size_t(j)] = 0.0;
            touched[std::size_t(j)] = 0;
        }
        columns.clear();
        A.offsets.push_back(A.column.size());
    }
    return A;
}

}  // namespace subdfit
