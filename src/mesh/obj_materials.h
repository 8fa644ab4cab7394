#pragma once
// An OBJ's materials from its MTL libraries (`mtllib`), as metallic-roughness materials: the
// diffuse colour Kd (and its map, map_Kd) is the base colour, dissolve d (or 1 − Tr) its alpha,
// the specular exponent Ns a roughness (√(2 / (Ns + 2)), the usual Blinn-Phong match), not
// metallic. Other statements (Ka, Ks, illum, bump maps, ...) are named in one warning.
#include <filesystem>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesh/material.h"

namespace subdfit::mesh::obj {

struct MaterialLibrary {
    MaterialSet set;
    std::vector<std::string> names;           // set.materials[i] is `newmtl names[i]`
    void add(std::string name);               // a new material of that name
    int find(const std::string& name) const;  // -1 when absent; the first of a repeated name

private:
    std::unordered_map<std::string, int> index_;
};

// Reads every library (names as the OBJ wrote them, relative to `objPath`'s folder, which they
// may not leave, symlinks followed: io/asset_folder.h) and the images their maps name (each
// file decoded once, all within io::kMaxImagePixelsPerFile). A missing library or image is a
// warning (the surface renders without it); a malformed one, or one outside the folder or not a
// regular file, an error naming the file and line.
struct LibraryUse {
    std::string name;
    int line = 0;  // of the mtllib statement
};
MaterialLibrary readMaterialLibraries(const std::filesystem::path& objPath, const std::vector<LibraryUse>& libraries);

}  // namespace subdfit::mesh::obj
