#pragma once
// Disjoint sets of 0..n−1 (union-find with path halving): the polygons of a coded cage's
// triangles, a remesh's regions and fans. Each set's root is its smallest member.
#include <algorithm>
#include <numeric>
#include <vector>

namespace subdfit {

class DisjointSets {
public:
    explicit DisjointSets(int n) : parent_(static_cast<size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }
    int find(int x) {
        while (parent_[size_t(x)] != x) x = parent_[size_t(x)] = parent_[size_t(parent_[size_t(x)])];
        return x;
    }
    void join(int a, int b) {
        a = find(a), b = find(b);
        if (a != b) parent_[size_t(std::max(a, b))] = std::min(a, b);
    }

private:
    std::vector<int> parent_;
};

}  // namespace subdfit
