#include "geometry/parallel_in_scopes.h"

#include <optional>

#include "common/parallel_chunks.h"
#include "tessella/surface_face.h"

namespace tessella {

void for_each_in_scopes(const SurfaceFace& face, std::size_t count, std::size_t chunk,
                        const std::function<void(std::size_t)>& fn) {
  const bool scoped = SurfaceFace::FastEvaluation::active(face);
  ChunkQueue queue(count, chunk);
  run_chunks(queue, scoped ? worker_threads() : 1, [&](bool calling) {
    // The other threads on their own copy of the surface (no OCCT object
    // with mutable state shared); the caller keeps its open scope.
    std::optional<SurfaceFace::FastEvaluation> fast;
    if (!calling) fast.emplace(face, true);
    std::size_t begin = 0, end = 0;
    while (queue.next(begin, end))
      for (std::size_t k = begin; k < end; ++k) fn(k);
  });
}

}  // namespace tessella
