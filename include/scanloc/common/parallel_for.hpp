#pragma once
// Splits a loop over [0, count) into contiguous chunks run on the machine's cores: the caller's
// thread takes the first chunk, the workers of a persistent pool the others (they sleep while
// idle), and all have finished on return.
// The chunks are in index order, so a caller that merges per-chunk results in chunk order gets
// what the serial loop gives. Loops shorter than min_chunk per core run serially, here.

#include <cstddef>
#include <functional>

namespace scanloc {

// The threads loops may use, the caller's included: 1 (the default) runs every loop on the
// calling thread, 0 is one per hardware thread. Takes effect from the next loop; results do not
// depend on it (chunks merge in index order).
void SetParallelThreads(std::size_t threads);
// The threads loops use now, the caller's included.
std::size_t ParallelThreads();

// The number of chunks ParallelFor uses for `count` items: 1 … hardware threads.
std::size_t ParallelChunkCount(std::size_t count, std::size_t min_chunk);

// Calls body(chunk, begin, end) once for each of ParallelChunkCount(count, min_chunk) chunks.
// An exception thrown by a body is rethrown here after every chunk has finished.
void ParallelFor(
    std::size_t count, std::size_t min_chunk,
    const std::function<void(std::size_t chunk, std::size_t begin, std::size_t end)>& body);

}  // namespace scanloc
