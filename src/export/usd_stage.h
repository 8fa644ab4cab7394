#pragma once
// The shipped asset as one USD layer: /Asset (an Xform, kind "component", the default prim)
// holding /Asset/Cage (export/usd_cage.h) bound to /Asset/Materials/Surface
// (export/usd_material.h), with the images that material reads. docs/usd.md says what each
// renderer and DCC tool makes of it.
#include <string>
#include <vector>

#include "export/subd_format.h"
#include "export/usd_material.h"

namespace subdfit::exporter {

// Stage metadata: what the source file says of its axes and units. USD's own fallbacks (Y up,
// centimetres) where it says nothing: written all the same, so that no reader has to guess.
struct UsdUnits {
    std::string upAxis = "Y";
    double metersPerUnit = 0.01;
};

struct UsdStage {
    std::string layer;                     // .usda text
    std::vector<UsdTextureFile> textures;  // the images it names
};

// `textureLocation` goes before each image's name in the layer's asset paths: "" inside the
// package, e.g. "asset.usdz" for a layer beside it (read as "asset.usdz[name]", USD's path of a
// file inside a package). `asset` as readSubd() returns it: what ships.
UsdStage usdStage(const SubdAsset& asset, const UsdUnits& units, const std::string& textureLocation = "");

}  // namespace subdfit::exporter
