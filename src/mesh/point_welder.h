#pragma once
// Welds points closer than a tolerance into one index: the same limit point evaluated from two
// neighbouring patches agrees to rounding, not bit for bit, so exact comparison would split it.
// A hash grid of cells twice the tolerance, each query checking the 8 cells a point within the
// tolerance can lie in, so points that straddle a cell border still meet. The grid is one
// open-addressed table of cells, each the head of a list of its points: no allocation per cell,
// which at millions of points is what the welding would otherwise cost.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace subdfit::mesh {

class PointWelder {
public:
    explicit PointWelder(float tolerance) : tolerance_(tolerance) {}

    // The index of the first point within the tolerance of `p`, or `nextIndex` (then
    // incremented) for a new one.
    int indexOf(const glm::vec3& p, int& nextIndex);

private:
    using Cell = std::array<std::int64_t, 3>;
    struct Slot {
        Cell cell{};
        int head = -1;  // the cell's first point, into points_; -1: an empty slot
        int tail = -1;  // its last: points are searched in the order they came
    };
    struct Point {
        glm::vec3 position;
        int index;
        int next;  // the cell's next point; -1: none
    };
    Slot* find(const Cell& cell);  // the cell's slot, or the empty one where it would go
    void grow();

    float tolerance_;
    std::vector<Slot> slots_;  // a power of two in size, at most half full
    std::size_t used_ = 0;
    std::vector<Point> points_;
};

// `points` with each replaced by the first of them within a millionth of their extent (as
// surface::weldedMesh welds): a limit point two patches evaluated to rounding becomes one value,
// so that a quantiser or a simplifier sees one point, not a crack.
std::vector<glm::vec3> coincidentPointsMerged(const std::vector<glm::vec3>& points);

}  // namespace subdfit::mesh
