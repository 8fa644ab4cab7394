#pragma once
// An OBJ's materials from its MTL libraries (`mtllib`), as metallic-roughness materials: the
// diffuse colour Kd (and its map, map_Kd) is the base colour, dissolve d (or 1 − Tr) its alpha,
// the specular exponent Ns a roughness (√(2 / (Ns + 2)), the usual Blinn-Phong match), not
// metallic. Other statements (Ka, Ks, illum, bump maps, ...) are named in one warning.
#include <filesystem>
#include <string>
#include <vector>

#include "mesh/material.h"

namespace subdfit::mesh::obj {

struct MaterialLibrary {
    MaterialSet set;
    std::vector<std::string> names;  // set.materials[i] is `newmtl names[i]`
    int find(const std::string& name) const;  // -1 when absent
};

// Reads every library (names as the OBJ wrote them, relative to `objPath`'s folder, which they
// may not leave) and the images their maps name. A missing library or image is a warning (the
// surface renders without it), a malformed one an error naming the file and line.
struct LibraryUse {
    std::string name;
    int line = 0;  // of the mtllib statement
};
MaterialLibrary readMaterialLibraries(const std::filesystem::path& objPath, const std::vector<LibraryUse>& libraries);

}  // namespace subdfit::mesh::obj
