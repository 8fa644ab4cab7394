#pragma once
// `decode --max-error E`: the coarsest density whose surface lies within E of the finest one
// decode may write of the same asset (its reference tessellation: the most segments within
// codec::kMaxDecodeTriangles, 64 and what the decode budget has left). The error of a density is the
// largest sampled distance between its triangles and the reference's, both ways
// (surface_error.h); it falls as the segments rise, so the segments are found by bisection.
#include "codec/decode_budget.h"
#include "codec/decode_density.h"
#include "codec/subd_format.h"

namespace subdfit::exporter {

// E in the asset's units, or as a fraction of the reference tessellation's bounding box diagonal.
struct ErrorBound {
    double value = 0.0;
    bool ofDiagonal = false;
};

struct ErrorDensity {
    codec::DecodeDensity density;
    double maxDistance = 0.0;  // of `density` to the reference, in the asset's units
    double bound = 0.0;        // E in the asset's units
    int referenceSegments = 0;
    bool clamped = false;  // E was below kResolvableFraction of the diagonal: the finest density
};

// The smallest error, as a fraction of the reference's diagonal, that float positions resolve.
inline constexpr double kResolvableFraction = 1e-6;

// The reference's vertices and triangles are spent from `budget` (named in its refusals). A bound
// below kResolvableFraction of the diagonal is clamped to the finest density, with a warning.
ErrorDensity densityWithin(const codec::SubdAsset& asset, const ErrorBound& bound, codec::DecodeBudget& budget);

}  // namespace subdfit::exporter
