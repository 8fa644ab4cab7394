#pragma once
// One way to ship the reference as triangles at a byte budget without subdfit (baselines.h says
// how each is made the strongest honest version of itself): what the route weighs a cage
// against, report.json lists and comparison.png draws. A new baseline is a class here and a line
// in triangleBaselinesFor; the route, the report and the picture iterate the list.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gl/program_cache.h"
#include "simplify/compare/baselines.h"
#include "simplify/compare/compare_level.h"
#include "simplify/compare/quality.h"

namespace subdfit::fit {
class FitScene;
}

namespace subdfit::simplify {

// How much of the reference a triangle baseline holds within the budget.
enum class Holds { Part, EveryTriangle, Whole };  // Whole: every triangle and every texel

class TriangleBaseline {
public:
    virtual ~TriangleBaseline() = default;
    virtual std::string name() const = 0;   // in report.json and the route ("decimation")
    virtual std::string title() const = 0;  // its column in comparison.png ("decimation + Draco")
    // Why it cannot be made on this machine (a tool not on PATH); empty where it can.
    virtual std::string unavailable() const { return {}; }
    // Its file written under settings.dir, measured as every baseline is.
    virtual Quality ship(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                         const BaselineSettings& settings) const = 0;
    // How much of the reference `shipped` (what ship made) holds.
    virtual Holds holds(const fit::FitScene&, const Quality& /*shipped*/) const { return Holds::Part; }
};

// A baseline as made: its name, title and quality.
struct MadeBaseline {
    std::string name, title;
    Quality quality;
};

// Whether the triangle baselines keep the reference's materials (textured or a plain colour), as
// a user's pipeline would.
bool shipsMaterials(const fit::FitScene& scene);

// Whether the reference is shaded flat, every triangle with vertices of its own and its face's
// normal (as a glTF primitive without normals is read, or a file without normals whose every
// corner has texture coordinates of its own): then its welded triangles drawn without normals,
// as viewers draw a file that ships none, look just as it does.
bool shadedFlat(const fit::FitScene& scene);

// The triangle baselines `level` makes for `scene`: decimation + Draco first (the route always
// weighs it), then gltfpack (fast and up), then clustering (all; untextured).
std::vector<std::unique_ptr<TriangleBaseline>> triangleBaselinesFor(const fit::FitScene& scene, CompareLevel level);

}  // namespace subdfit::simplify
