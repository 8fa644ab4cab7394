#include "export/usd/usd_stage.h"

#include <algorithm>
#include <cmath>

namespace subdfit::exporter {

UsdStage usdStage(const codec::SubdAsset& asset, const std::string& textureLocation) {
    const surface::SurfaceMaps& maps = asset.maps;
    const std::vector<UsdTexCoords> texCoords = usdTexCoords(maps);
    const subdiv::RefinedCage cage = usdCageOf(asset.cage, !texCoords.empty());
    usda::Layer layer;
    layer.line("#usda 1.0");
    layer.line("(");
    layer.line("    defaultPrim = \"Asset\"");
    layer.line("    doc = \"subdfit: a Catmull-Clark cage with its displacement and appearance maps (docs/usd.md)\"");
    layer.line("    metersPerUnit = 1");
    layer.line("    upAxis = \"Y\"");
    layer.line(")");
    layer.blank();

    const bool material = hasUsdMaterial(maps);
    float reach = 0.0f;
    for (float h : maps.displacement) reach = std::max(reach, std::abs(h));
    layer.block("def Xform \"Asset\" (kind = \"component\")");
    writeCagePrim(layer, cage, texCoords,
                  {.name = "Cage", .material = material ? "/Asset/Materials/Surface" : "", .reach = reach});
    UsdStage stage;
    if (material) {
        layer.block("def Scope \"Materials\"");
        stage.textures = writeMaterialPrim(layer, maps, "/Asset/Materials/Surface", [&](const std::string& name) {
            return textureLocation.empty() ? name : textureLocation + "[" + name + "]";
        });
        layer.end();
    }
    layer.end();
    stage.layer = layer.text();
    return stage;
}

}  // namespace subdfit::exporter
