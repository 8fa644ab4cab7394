#pragma once
// The heights fine-tuned as the decoder reads them. Rounding to the coding's steps has no useful
// derivative, but the coded surface's error has one: each step draws the heights as coded
// (codec::codedValues) and moves the heights as fitted by the gradient estimated there (a
// straight-through estimate), so the fit chooses which way each height rounds. At the few bits
// the budgets ask for, the rounding, not the fit, is what the asset loses most to
// (docs/simplify.md, "The heights fitted as coded").
#include <functional>

#include "fit/fit_run.h"

namespace subdfit::fit {

struct CodedRefinementSettings {
    int bits = 4;     // the heights' coding (codec::SubdPrecision::displacementBits)
    int steps = 200;  // at most
    int judgeEvery = 25;
    int judgedWorse = 2;  // judgments in a row above the lowest end it
    // Adam's step, in quantisation steps (at 4 bits on the README demo, half the fit's own for
    // heights): a fiftieth gained less there, a twentieth and a quarter nothing.
    float stepFraction = 0.01f;
};

struct CodedRefinement {
    int steps = 0;                           // taken
    int bestStep = 0;                        // 0: the start stayed the lowest
    int overBudget = 0;                      // judgments `fits` refused
    double startLoss = 0.0, bestLoss = 0.0;  // the judge's, of the heights as coded
    double seconds = 0.0;
};

// Refines `run`'s heights (the fitter's other groups, the cage included, stay) with `judge` (a
// loss of the fitter's current state on views the caller trusts) read every judgeEvery steps on
// the heights as coded, where `fits` (the fitter holding them as fitted; none: always) admits
// them (refined heights are rougher and code larger); leaves the fitter holding the judged
// lowest, as fitted (coded, they decode to what was judged). The fitter's rates and turns are
// as they were after.
CodedRefinement refineAsCoded(FitRun& run, const CodedRefinementSettings& settings,
                              const std::function<double()>& judge, const std::function<bool()>& fits = {});

}  // namespace subdfit::fit
