#pragma once
// Welds points closer than a tolerance into one index: the same limit point evaluated from two
// neighbouring patches agrees to rounding, not bit for bit, so exact comparison would split it.
// A hash grid of cell = tolerance, each query checking the 27 cells around it, so points that
// straddle a cell border still meet.
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

namespace subdfit::mesh {

class PointWelder {
public:
    explicit PointWelder(float tolerance) : cell_(tolerance) {}

    // The index of the first point within the tolerance of `p`, or `nextIndex` (then
    // incremented) for a new one.
    int indexOf(const glm::vec3& p, int& nextIndex);

private:
    float cell_;
    std::unordered_map<long long, std::vector<std::pair<glm::vec3, int>>> cells_;
};

// `points` with each replaced by the first of them within a millionth of their extent (as
// surface::weldedMesh welds): a limit point two patches evaluated to rounding becomes one value,
// so that a quantiser or a simplifier sees one point, not a crack.
std::vector<glm::vec3> coincidentPointsMerged(const std::vector<glm::vec3>& points);

}  // namespace subdfit::mesh
