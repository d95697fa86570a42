// A loop over independent indices on every core, each worker evaluating the
// face in a span-cached scope of its own (SurfaceFace::FastEvaluation): the
// scopes' span polynomials give the same numbers on every thread, so a result
// that depends on its own index alone is the same on any thread count. Where
// the caller evaluates without a scope (OCCT's own evaluation, which no
// worker's scope would match bit for bit) the loop runs on the calling thread
// alone.
#pragma once

#include <cstddef>
#include <functional>

namespace tessella {

class SurfaceFace;

// fn(k) for k in [0, count), in chunks of `chunk` indices claimed in order.
void for_each_in_scopes(const SurfaceFace& face, std::size_t count, std::size_t chunk,
                        const std::function<void(std::size_t)>& fn);

}  // namespace tessella
