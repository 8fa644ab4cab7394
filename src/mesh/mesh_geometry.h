#pragma once
// Derived geometry of a PolygonMesh that renderers need: triangles and vertex normals. All
// expect a mesh that passed validateMesh (broken indices are a SUBDFIT_CHECK failure).
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// Fan triangulation of every face (for reference meshes). Faces tagged as holes are left out,
// as OpenSubdiv does not render them; the result has no tags. Positions are shared unchanged.
PolygonMesh triangulated(const PolygonMesh& mesh);

// Area-weighted vertex normals (each face contributes its vector area). Never NaN: a vertex
// whose faces have no area, or that no face uses, gets +Z.
std::vector<glm::vec3> vertexNormals(const PolygonMesh& mesh);

// The normals `mesh` is shaded with: the author's (mesh.normals) where the file has them, else
// vertexNormals() (how a dense reference without normals is meant to look).
std::vector<glm::vec3> shadingNormals(const PolygonMesh& mesh);

// Whether every position has one shading normal however its vertices split (texture seams split
// vertices; hard edges split their normals too): then a copy welded by position, with those
// normals, shades as the mesh does.
bool oneNormalPerPosition(const PolygonMesh& mesh);

// A triangle mesh as glTF viewers draw a primitive without normals (glTF 2.0, 3.7.2.1: flat
// normals): every triangle its own three vertices (texture coordinates and colours kept) with
// its face's unit normal (+Z where it has no area).
PolygonMesh flatShaded(const PolygonMesh& triangles);

// The mean length of the faces' edges (an edge shared by two faces counts twice): the scale of
// a cage, which perturbations, steps and ray reaches are measured against.
float meanEdgeLength(const PolygonMesh& mesh);
// Whether any face is not a quad: OpenSubdiv splits such a face into ptex faces (one per
// corner) whose edges are half the face's, each with a whole map tile.
bool hasNonQuadFaces(const PolygonMesh& mesh);
// How many faces are quads.
int quadCount(const PolygonMesh& mesh);

}  // namespace subdfit::mesh
