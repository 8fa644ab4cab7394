#pragma once
#include <array>
#include <string_view>
#include <utility>

#include "util/named_enum.h"

namespace subdfit::simplify {

// How much comparison a run makes beside what it ships:
//  none: only what chooses the route (decimation + Draco at the budget, on the held-out views);
//        no baselines/ folder, no comparison.png, no surface distances;
//  fast: the triangle baselines too (gltfpack), each with its files and held-out scores;
//  full: also the bake route, the surface distances and comparison.png;
//  all:  full, and every triangle baseline subdfit knows, those that rarely lead too.
enum class CompareLevel { None, Fast, Full, All };

}  // namespace subdfit::simplify

template <>
struct subdfit::EnumNames<subdfit::simplify::CompareLevel> {
    using L = simplify::CompareLevel;
    static constexpr std::array names{
        std::pair{L::None, std::string_view("none")}, std::pair{L::Fast, std::string_view("fast")},
        std::pair{L::Full, std::string_view("full")}, std::pair{L::All, std::string_view("all")}};
};
