#pragma once
// The shipped asset as one USD layer: /Asset (an Xform, kind "component", the default prim)
// holding /Asset/Cage (export/usd/usd_cage.h) bound to /Asset/Materials/Surface
// (export/usd/usd_material.h), with the images that material reads. docs/usd.md says what each
// renderer and DCC tool makes of it.
#include <string>
#include <vector>

#include "codec/subd_format.h"
#include "export/usd/usd_material.h"

namespace subdfit::exporter {

struct UsdStage {
    std::string layer;                     // .usda text
    std::vector<UsdTextureFile> textures;  // the images it names
};

// The stage is Y up in metres, as the glTF beside it (glTF 2.0, 3.4): a reader opening both, or
// the source OBJ (read as Blender and three.js read it, a unit a metre), sees one size.
// `textureLocation` goes before each image's name in the layer's asset paths: "" inside the
// package, e.g. "asset.usdz" for a layer beside it (read as "asset.usdz[name]", USD's path of a
// file inside a package). `asset` as codec::readSubd() returns it: what ships.
UsdStage usdStage(const codec::SubdAsset& asset, const std::string& textureLocation = "");

}  // namespace subdfit::exporter
