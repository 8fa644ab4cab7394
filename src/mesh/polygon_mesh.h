#pragma once
// A polygon mesh as read from disk: the Catmull-Clark cage, or a reference asset (which is
// triangulated before rendering). Indices are 0-based; faces are stored concatenated.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <memory>
#include <string>
#include <vector>

#include "mesh/material.h"

namespace subdfit::mesh {

// OpenSubdiv's OBJ `t` tags (see assets' osd-shapes/README.md), kept so that a fitted cage
// is written back with the same creases, corners, holes and rules as it was read.
enum class BoundaryInterpolation { None = 0, EdgeAndCorner = 1, EdgeOnly = 2 };
enum class CreaseMethod { Uniform, Chaikin };
enum class TriangleSubdivision { Catmark, Smooth };

struct Crease {
    int v0 = 0, v1 = 0;
    float sharpness = 0.0f;  // 10 = infinitely sharp
    friend bool operator==(const Crease&, const Crease&) = default;
};

struct Corner {
    int vertex = 0;
    float sharpness = 0.0f;
    friend bool operator==(const Corner&, const Corner&) = default;
};

struct SubdivisionTags {
    std::vector<Crease> creases;
    std::vector<Corner> corners;
    std::vector<int> holes;  // face indices
    // OpenSubdiv's regression defaults when a file says nothing.
    BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly;
    int faceVaryingBoundary = 1;
    CreaseMethod creaseMethod = CreaseMethod::Uniform;
    TriangleSubdivision triangles = TriangleSubdivision::Catmark;
    // Tags that are read but not applied (e.g. hierarchical edits): written back verbatim.
    std::vector<std::string> passthrough;
    // Which tags the file named explicitly (so a writer can reproduce exactly those).
    bool hasBoundary = false, hasFaceVaryingBoundary = false;
    bool hasCreaseMethod = false, hasTriangles = false;
    friend bool operator==(const SubdivisionTags&, const SubdivisionTags&) = default;
};

// What a reader takes from a file: the geometry (and OpenSubdiv tags) only, as a cage needs,
// or also its appearance, as a reference's renders need.
enum class MeshContent { Geometry, WithAppearance };

struct PolygonMesh {
    std::vector<glm::vec3> positions;
    std::vector<int> faceSizes;
    std::vector<int> faceIndices;  // concatenated, sum(faceSizes) entries
    SubdivisionTags tags;
    std::string sourcePath;  // for error messages

    // A reference's appearance, read only when asked for (mesh_loader.h's loadReference): per
    // vertex texture coordinates (TEXCOORD_0; empty when none), colours (COLOR_0, linear RGBA;
    // empty when none) and the author's unit shading normals (NORMAL; empty when the file has
    // none, and mesh_geometry.h's shadingNormals() computes them), and per face its material in
    // `materials` (all empty for a mesh without materials: a grey surface).
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> colors;
    std::vector<int> faceMaterials;
    std::shared_ptr<const MaterialSet> materials;
    bool hasAppearance() const { return materials != nullptr || !colors.empty(); }

    int vertexCount() const { return int(positions.size()); }
    int faceCount() const { return int(faceSizes.size()); }
};

}  // namespace subdfit::mesh
