#pragma once
// The kinds of map a cage carries, each described once, as OpenSubdiv's Far describes its patch
// types: what it holds, where it lives, how the passes, the file and the exporters name it. Code
// that is the same for every kind loops over kMapKinds; code truly specific to one kind (what a
// height does to the surface, how a colour is shaded, how glTF and USD ship it) names it.
#include <array>
#include <cstdint>
#include <initializer_list>
#include <string_view>

namespace subdfit::kinds {

enum class MapKind : std::uint8_t { Displacement, NormalMap, BaseColor, MetallicRoughness };
inline constexpr int kMapKindCount = 4;

// Which lattice a kind's nodes lie on: the geometric maps share one, the appearance maps a finer
// one of their own (or a texture atlas's texel grid).
enum class MapLattice : std::uint8_t { Geometric, Appearance };

struct MapKindInfo {
    MapKind kind;
    std::string_view name;  // the parameter group's name, in logs and reports ("normal_map")
    std::string_view word;  // in --maps ("normal"); empty: the scene's materials decide, not the user
    MapLattice lattice;
    int channels;                   // values per node
    std::array<float, 3> initial;   // per channel, until a bake (or the fit) says otherwise
    bool unitRange;                 // values in [0, 1] (colours, fractions); else unbounded
    std::array<char, 4> section;    // its asset.subd section
    std::string_view rasterDefine;  // the patch raster pass's variant define; empty: none (heights
                                    // move the surface: the tessellator's variant, SUBDFIT_DISPLACEMENT)
    std::uint32_t seed;             // salts the group's own stream of perturbation signs
    float epsilon, learningRate;    // the group's default perturbation and Adam step, in its units
};

// In MapKind order. Heights are in the normalised frame (scene radius 1), tangent offsets are
// dimensionless, colours sRGB values and roughness / metallic fractions.
inline constexpr std::array<MapKindInfo, kMapKindCount> kMapKinds{{
    {.kind = MapKind::Displacement,
     .name = "displacement",
     .word = "displacement",
     .lattice = MapLattice::Geometric,
     .channels = 1,
     .initial = {0.0f, 0.0f, 0.0f},
     .unitRange = false,
     .section = {'D', 'I', 'S', 'P'},
     .rasterDefine = "",
     .seed = 0x68e31da4u,
     .epsilon = 0.004f,
     .learningRate = 0.003f},
    {.kind = MapKind::NormalMap,
     .name = "normal_map",
     .word = "normal",
     .lattice = MapLattice::Geometric,
     .channels = 2,
     .initial = {0.0f, 0.0f, 0.0f},
     .unitRange = false,
     .section = {'N', 'O', 'R', 'M'},
     .rasterDefine = "SUBDFIT_NORMAL_MAP",
     .seed = 0xb5297a4du,
     .epsilon = 0.05f,
     .learningRate = 0.01f},
    {.kind = MapKind::BaseColor,
     .name = "base_color",
     .word = "",
     .lattice = MapLattice::Appearance,
     .channels = 3,
     .initial = {0.5f, 0.5f, 0.5f},  // mid grey
     .unitRange = true,
     .section = {'B', 'C', 'O', 'L'},
     .rasterDefine = "SUBDFIT_BASE_COLOR_MAP",
     .seed = 0x1b56c4e9u,
     .epsilon = 0.03f,
     .learningRate = 0.004f},
    {.kind = MapKind::MetallicRoughness,
     .name = "metallic_roughness",
     .word = "",
     .lattice = MapLattice::Appearance,
     .channels = 2,                  // (roughness, metallic)
     .initial = {0.5f, 0.0f, 0.0f},  // half rough, dielectric
     .unitRange = true,
     .section = {'M', 'T', 'R', 'G'},
     .rasterDefine = "SUBDFIT_METALLIC_ROUGHNESS_MAP",
     .seed = 0x7f4a7c15u,
     .epsilon = 0.05f,
     .learningRate = 0.004f},
}};

static_assert([] {
    for (int k = 0; k < kMapKindCount; ++k)
        if (kMapKinds[std::size_t(k)].kind != MapKind(k)) return false;
    return true;
}());

constexpr const MapKindInfo& info(MapKind kind) { return kMapKinds[std::size_t(kind)]; }

// The kind whose asset.subd section `tag` is; null for another section.
const MapKindInfo* kindWithSection(const std::array<char, 4>& tag);

// A set of kinds, as the bits of a shader variant are: which maps a scene fits (the "effects"
// it simulates), which a pass applies.
class MapKinds {
public:
    constexpr MapKinds() = default;
    constexpr MapKinds(std::initializer_list<MapKind> kinds) {
        for (MapKind k : kinds) set(k);
    }
    constexpr bool has(MapKind k) const { return (bits_ >> unsigned(k)) & 1u; }
    constexpr void set(MapKind k, bool on = true) {
        bits_ = on ? std::uint8_t(bits_ | (1u << unsigned(k))) : std::uint8_t(bits_ & ~(1u << unsigned(k)));
    }
    constexpr bool any(MapLattice lattice) const {
        for (const MapKindInfo& i : kMapKinds)
            if (i.lattice == lattice && has(i.kind)) return true;
        return false;
    }
    constexpr bool geometric() const { return any(MapLattice::Geometric); }
    constexpr bool appearance() const { return any(MapLattice::Appearance); }
    constexpr bool any() const { return bits_ != 0; }
    // Every kind on `lattice`.
    static constexpr MapKinds on(MapLattice lattice) {
        MapKinds out;
        for (const MapKindInfo& i : kMapKinds) out.set(i.kind, i.lattice == lattice);
        return out;
    }
    friend constexpr MapKinds operator|(MapKinds a, MapKinds b) { return MapKinds(std::uint8_t(a.bits_ | b.bits_)); }
    friend constexpr MapKinds operator&(MapKinds a, MapKinds b) { return MapKinds(std::uint8_t(a.bits_ & b.bits_)); }
    friend constexpr bool operator==(MapKinds, MapKinds) = default;

private:
    constexpr explicit MapKinds(std::uint8_t bits) : bits_(bits) {}
    std::uint8_t bits_ = 0;
};

}  // namespace subdfit::kinds
