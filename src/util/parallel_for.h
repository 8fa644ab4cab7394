#pragma once
// body(i) for every i in [begin, end): on every core (TBB), or in order where the build has no
// threads (SUBDFIT_NO_THREADS: the WebAssembly decoder, the fuzzers). The body must not depend on
// the order. A caller with threads links TBB.
#ifdef SUBDFIT_NO_THREADS
namespace subdfit {
template <class Body>
void parallelFor(int begin, int end, const Body& body) {
    for (int i = begin; i < end; ++i) body(i);
}
}  // namespace subdfit
#else
#include <tbb/parallel_for.h>
namespace subdfit {
template <class Body>
void parallelFor(int begin, int end, const Body& body) {
    tbb::parallel_for(begin, end, body);
}
}  // namespace subdfit
#endif
