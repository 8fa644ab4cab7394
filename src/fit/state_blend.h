#pragma once
// States between a fit's start and its end: the way back from a fitted state that codes larger
// than a budget allows (fit/coded_refinement.h, simplify's verdict on the fit).
#include <functional>
#include <vector>

#include "fit/fit_state.h"

namespace subdfit::fit {

// `from` + t (`to` - `from`), element by element (equal sizes).
std::vector<float> between(const std::vector<float>& from, const std::vector<float>& to, float t);

// `to` with each group's parameters a fraction t of the way from `from`'s (the same groups, as
// CageFitter::state() of one fitter gives them); the moments, schedule and history stay `to`'s.
FitState between(const FitState& from, const FitState& to, float t);

// Bisections of the way back: a sixteenth of the way at most is given up.
inline constexpr int kBudgetBisections = 4;

// Where holds(1) is false: the largest t in [0, 1) at which `holds(t)` is true, assuming it holds
// below some t, bisected `bisections` times (a 2^-bisections of the way at most is given up); 0
// where none of the t tried holds. Calls holds(t) once per t tried, in order.
float furthestThatHolds(const std::function<bool(float)>& holds, int bisections);

}  // namespace subdfit::fit
