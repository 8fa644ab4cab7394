#include "simplify/remesh/cross_field.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "util/parallel_for.h"

namespace subdfit::simplify::remesh {
namespace {

glm::vec3 inTangentPlane(const glm::vec3& v, const glm::vec3& n) { return v - n * glm::dot(n, v); }

// Some unit tangent of n, the same for the same n.
glm::vec3 anyTangent(const glm::vec3& n) {
    const glm::vec3 axis = std::abs(n.x) < 0.6f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(n, axis));
}

glm::vec3 unitTangent(const glm::vec3& v, const glm::vec3& n) {
    const glm::vec3 t = inTangentPlane(v, n);
    const float length = glm::length(t);
    return length > 1e-12f ? t / length : anyTangent(n);
}

// The point nearest both p0 and p1 on the line where their tangent planes meet (the midpoint
// where the planes are parallel): where two samples' lattices are compared.
glm::vec3 meetingPoint(const glm::vec3& p0, const glm::vec3& n0, const glm::vec3& p1, const glm::vec3& n1) {
    // Minimise |x − p0|² + |x − p1|² subject to n0·x = n0·p0, n1·x = n1·p1 (Lagrange); the
    // small constant keeps parallel planes finite.
    const float n0p0 = glm::dot(n0, p0), n0p1 = glm::dot(n0, p1), n1p0 = glm::dot(n1, p0), n1p1 = glm::dot(n1, p1);
    const float c = glm::dot(n0, n1), inverse = 1.0f / (1.0f - c * c + 1e-4f);
    const float l0 = 2.0f * (n0p1 - n0p0 - c * (n1p0 - n1p1)) * inverse;
    const float l1 = 2.0f * (n1p0 - n1p1 - c * (n0p1 - n0p0)) * inverse;
    return 0.5f * (p0 + p1) - 0.25f * (n0 * l0 + n1 * l1);
}

// The lattice point of (o, q, n × q, scale) at or below `p` in both lattice directions.
glm::vec3 latticeFloor(const glm::vec3& o, const glm::vec3& q, const glm::vec3& n, const glm::vec3& p, float scale) {
    const glm::vec3 t = glm::cross(n, q), d = p - o;
    return o + q * (std::floor(glm::dot(q, d) / scale) * scale) + t * (std::floor(glm::dot(t, d) / scale) * scale);
}

glm::vec3 latticeRound(const glm::vec3& o, const glm::vec3& q, const glm::vec3& n, const glm::vec3& p, float scale) {
    const glm::vec3 t = glm::cross(n, q), d = p - o;
    return o + q * (std::round(glm::dot(q, d) / scale) * scale) + t * (std::round(glm::dot(t, d) / scale) * scale);
}

// Of the four lattice points of each sample around their meeting point, the closest pair.
std::pair<glm::vec3, glm::vec3> closestLatticePoints(const glm::vec3& p0, const glm::vec3& n0, const glm::vec3& q0,
                                                     const glm::vec3& o0, const glm::vec3& p1, const glm::vec3& n1,
                                                     const glm::vec3& q1, const glm::vec3& o1, float scale) {
    const glm::vec3 t0 = glm::cross(n0, q0), t1 = glm::cross(n1, q1);
    const glm::vec3 middle = meetingPoint(p0, n0, p1, n1);
    const glm::vec3 base0 = latticeFloor(o0, q0, n0, middle, scale), base1 = latticeFloor(o1, q1, n1, middle, scale);
    float best = std::numeric_limits<float>::infinity();
    std::pair<glm::vec3, glm::vec3> closest{base0, base1};
    for (int a = 0; a < 4; ++a) {
        const glm::vec3 c0 = base0 + (q0 * float(a & 1) + t0 * float(a >> 1)) * scale;
        for (int b = 0; b < 4; ++b) {
            const glm::vec3 c1 = base1 + (q1 * float(b & 1) + t1 * float(b >> 1)) * scale;
            const glm::vec3 d = c0 - c1;
            const float distance = glm::dot(d, d);
            if (distance < best) {
                best = distance;
                closest = {c0, c1};
            }
        }
    }
    return closest;
}

// A level's q from the finer level's, each coarse sample taking its children's average.
std::vector<glm::vec3> restrictedOrientation(const GraphLevel& fine, const std::vector<glm::vec3>& q,
                                             const GraphLevel& coarse) {
    std::vector<glm::vec3> sum(size_t(coarse.size()), glm::vec3(0.0f));
    std::vector<char> seen(size_t(coarse.size()), 0);
    for (int v = 0; v < fine.size(); ++v) {
        const size_t p = size_t(fine.parent[size_t(v)]);
        if (!seen[p]) {
            sum[p] = q[size_t(v)];
            seen[p] = 1;
        } else {
            const auto [mine, theirs] =
                closestDirections(sum[p], coarse.normals[p], q[size_t(v)], fine.normals[size_t(v)]);
            sum[p] = mine + theirs;
        }
    }
    for (size_t p = 0; p < sum.size(); ++p) sum[p] = unitTangent(sum[p], coarse.normals[p]);
    return sum;
}

// update(v) for every sample of `level`, an independent set at a time (on every core).
template <class Update>
void sweepOver(const GraphLevel& level, const Update& update) {
    for (const std::vector<int>& set : level.independentSets)
        parallelFor(0, int(set.size()), [&](int i) { update(set[size_t(i)]); });
}

}  // namespace

std::pair<glm::vec3, glm::vec3> closestDirections(const glm::vec3& q0, const glm::vec3& n0, const glm::vec3& q1,
                                                  const glm::vec3& n1) {
    const glm::vec3 a[2] = {q0, glm::cross(n0, q0)}, b[2] = {q1, glm::cross(n1, q1)};
    float best = -1.0f;
    std::pair<glm::vec3, glm::vec3> closest{q0, q1};
    for (const glm::vec3& x : a)
        for (const glm::vec3& y : b) {
            const float d = glm::dot(x, y);
            if (std::abs(d) > best) {
                best = std::abs(d);
                closest = {x, d < 0.0f ? -y : y};
            }
        }
    return closest;
}

LatticeStep latticeStep(const glm::vec3& oa, const glm::vec3& qa, const glm::vec3& na, const glm::vec3& ob,
                        float scale) {
    const glm::vec3 d = ob - oa;
    return {int(std::lround(glm::dot(d, qa) / scale)), int(std::lround(glm::dot(d, glm::cross(na, qa)) / scale))};
}

std::vector<glm::vec3> orientationField(const std::vector<GraphLevel>& levels, const FieldSweeps& sweeps) {
    const GraphLevel& top = levels.back();
    std::vector<glm::vec3> q(size_t(top.size()));
    for (int v = 0; v < top.size(); ++v) q[size_t(v)] = anyTangent(top.normals[size_t(v)]);
    for (int l = int(levels.size()) - 1; l >= 0; --l) {
        const GraphLevel& level = levels[size_t(l)];
        const int orientationSweeps = level.size() <= sweeps.smallLevel ? sweeps.orientation : sweeps.fineOrientation;
        for (int sweep = 0; sweep < orientationSweeps; ++sweep)
            sweepOver(level, [&](int v) {
                const glm::vec3 n = level.normals[size_t(v)];
                glm::vec3 sum = q[size_t(v)];
                float weightSum = 0.0f;
                for (int k = level.offsets[size_t(v)]; k < level.offsets[size_t(v) + 1]; ++k) {
                    const int u = level.neighbors[size_t(k)];
                    const float w = level.weights[size_t(k)];
                    const auto [mine, theirs] = closestDirections(sum, n, q[size_t(u)], level.normals[size_t(u)]);
                    sum = unitTangent(mine * weightSum + theirs * w, n);
                    weightSum += w;
                }
                q[size_t(v)] = sum;
            });
        if (l == 0) break;
        const GraphLevel& finer = levels[size_t(l - 1)];
        std::vector<glm::vec3> next(size_t(finer.size()));
        for (int v = 0; v < finer.size(); ++v)
            next[size_t(v)] = unitTangent(q[size_t(finer.parent[size_t(v)])], finer.normals[size_t(v)]);
        q = std::move(next);
    }
    return q;
}

std::vector<glm::vec3> positionField(const std::vector<GraphLevel>& levels, const std::vector<glm::vec3>& orientation,
                                     const FieldSweeps& sweeps) {
    std::vector<std::vector<glm::vec3>> q(levels.size());
    q[0] = orientation;
    for (size_t l = 1; l < levels.size(); ++l) q[l] = restrictedOrientation(levels[l - 1], q[l - 1], levels[l]);

    std::vector<glm::vec3> o = levels.back().positions;
    for (int l = int(levels.size()) - 1; l >= 0; --l) {
        const GraphLevel& level = levels[size_t(l)];
        const std::vector<glm::vec3>& ql = q[size_t(l)];
        const int positionSweeps = level.size() <= sweeps.smallLevel ? sweeps.position : sweeps.finePosition;
        for (int sweep = 0; sweep < positionSweeps; ++sweep)
            sweepOver(level, [&](int v) {
                const glm::vec3 p = level.positions[size_t(v)], n = level.normals[size_t(v)];
                const float scale = level.scales[size_t(v)];
                glm::vec3 sum = o[size_t(v)];
                float weightSum = 0.0f;
                for (int k = level.offsets[size_t(v)]; k < level.offsets[size_t(v) + 1]; ++k) {
                    const int u = level.neighbors[size_t(k)];
                    const float w = level.weights[size_t(k)];
                    const auto [mine, theirs] = closestLatticePoints(
                        p, n, ql[size_t(v)], sum, level.positions[size_t(u)], level.normals[size_t(u)], ql[size_t(u)],
                        o[size_t(u)], 0.5f * (scale + level.scales[size_t(u)]));
                    sum = (mine * weightSum + theirs * w) / (weightSum + w);
                    sum -= n * glm::dot(n, sum - p);
                    weightSum += w;
                }
                o[size_t(v)] = latticeRound(sum, ql[size_t(v)], n, p, scale);
            });
        if (l == 0) break;
        const GraphLevel& finer = levels[size_t(l - 1)];
        std::vector<glm::vec3> next(size_t(finer.size()));
        for (int v = 0; v < finer.size(); ++v) {
            const glm::vec3 p = finer.positions[size_t(v)], n = finer.normals[size_t(v)];
            glm::vec3 from = o[size_t(finer.parent[size_t(v)])];
            from -= n * glm::dot(n, from - p);
            next[size_t(v)] = latticeRound(from, q[size_t(l - 1)][size_t(v)], n, p, finer.scales[size_t(v)]);
        }
        o = std::move(next);
    }
    return o;
}

}  // namespace subdfit::simplify::remesh
