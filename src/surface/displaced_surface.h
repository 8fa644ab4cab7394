#pragma once
// The CPU twin of the GPU surface: a cage's Catmull-Clark limit surface (OpenSubdiv), displaced
// along its normal by the displacement map, with a unit normal and a tangent frame everywhere
// (also where the limit derivatives collapse). Exports tessellate it, measurements sample it.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "mesh/polygon_mesh.h"
#include "subdiv/limit_evaluator.h"
#include "surface/surface_maps.h"

namespace subdfit::surface {

struct SurfaceVertex {
    glm::vec3 position;
    glm::vec3 normal;  // unit, of the displaced surface (of the limit surface: SurfaceMaps::shadingNormal)
    // xyz: unit, orthogonal to the normal, along dP/du; w = ±1 so that cross(normal, xyz) · w
    // points along dP/dv: the frame the normal map's (x, y) is expressed in.
    glm::vec4 tangent;
    // The displaced surface's derivatives along the ptex face's u and v (curvature term dropped;
    // the limit surface's where it shades): the frame the shading normal comes from.
    glm::vec3 dPdu, dPdv;
};

class DisplacedSurface {
public:
    // `maps` must outlive the surface (the cage is read here); without a displacement it gives the
    // limit surface.
    DisplacedSurface(const mesh::PolygonMesh& cage, const SurfaceMaps& maps);

    int ptexFaceCount() const { return evaluator_.ptexFaceCount(); }
    bool hasSurface(int face) const { return evaluator_.hasSurface(face, 0.5f, 0.5f); }

    // Every output finite.
    SurfaceVertex at(int face, float u, float v) const;

private:
    struct LimitPoint {
        glm::vec3 position, dPdu, dPdv, normal;
    };
    LimitPoint limitPoint(int face, float u, float v) const;
    float height(int face, float u, float v) const;
    glm::vec2 heightGradient(int face, float u, float v) const;

    const SurfaceMaps& maps_;
    subdiv::LimitEvaluator evaluator_;
    std::vector<glm::dvec3> patchPoints_;  // of cage_'s positions: each stencil applied once
};

}  // namespace subdfit::surface
