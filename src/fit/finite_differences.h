#pragma once
// The reference the SGE estimate is checked against (tests, `subdfit-bench gradient`): the
// total image loss of the current scene and its central finite differences per vertex
// coordinate, through the very same rasteriser.
#include <glm/vec3.hpp>
#include <vector>

#include "fit/cage_fitter.h"
#include "scene/target_set.h"

namespace subdfit::fit {

// Σ over the views of `targets` and their pixels of ‖I − T‖²: the loss whose gradient G estimates.
double totalImageLoss(CageFitter& fitter, const scene::TargetSet& targets);

// (f(θ + h e_i) − f(θ − h e_i)) / 2h for every coordinate of `base` (the fitter's vertices are
// left at `base` afterwards).
std::vector<double> vertexFiniteDifferences(CageFitter& fitter, const scene::TargetSet& targets,
                                            const std::vector<glm::vec3>& base, float h);

}  // namespace subdfit::fit
