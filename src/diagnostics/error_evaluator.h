// Diagnostics of paper §5 (not part of the product): measures the achieved error that the
// refinement criteria bound.
// Error evaluator: how far any triangle mesh is from the height-field samples.
//
// Every sample (column j, row i) is taken at its own horizontal position (x = j*spacingX,
// z = i*spacingY), the mesh is interpolated there linearly inside the triangle that contains
// it (in the x-z plane), and the error is |mesh height - sample height|. The mesh may use any
// embedding (vertices on samples, or odd rows shifted half a sample) and may reach past the
// data rectangle: only samples inside [0, (W-1)*spacingX] x [0, (H-1)*spacingY] count.
// Meant for tests, the CLI and benchmarks, not for per-frame code (it allocates).
#pragma once

#include <cstddef>
#include <cstdint>

#include "field/heightfield.h"

namespace hexlod {

struct ErrorStats {
    double maxError = 0.0;  // metres, largest error over the evaluated samples
    double p99Error = 0.0;  // metres, 99th percentile (nearest rank) over the evaluated samples
    double meanError = 0.0; // metres, mean over the evaluated samples
    int64_t evaluated = 0;  // samples that lie inside some triangle (each counted once)
    int64_t uncovered = 0;  // samples of the rectangle that no triangle contains (holes, gaps)
    int32_t worstColumn = -1, worstRow = -1; // sample (j, i) of maxError; the first in row order on a tie
    const char* error = nullptr; // null, or why nothing was evaluated (invalid input, no memory)
};

struct ErrorOptions {
    // Mesh heights are sample heights times this (> 0); errors are still reported in metres
    // of the field, i.e. divided by it.
    float verticalScale = 1.0f;
    // Evaluate only samples whose column and row are multiples of this (>= 1), e.g. to bound
    // the memory on huge fields: the evaluator allocates 4 bytes per sample it considers
    // (64 MB for 4096 x 4096). evaluated + uncovered then count those samples only.
    int32_t sampleStride = 1;
    // Compare with the field as the shifted embedding stores it (paper §4.7) instead of the
    // original samples: odd-row samples at x = (j + 0.5) * spacingX with height
    // (h(j) + h(j+1)) / 2, the last column clamped. Even rows are unchanged.
    bool shiftedOddRows = false;
};

/// Compares a triangle mesh with the samples of `field`.
/// positions: vertexCount vertices, each starting with x, y, z in metres (x east, y up,
///            z south; y already multiplied by options.verticalScale), strideFloats (>= 3)
///            floats apart, so an interleaved vertex array (position + normal, ...) fits as is.
/// indices:   triangle list, 3 per triangle, any winding; degenerate triangles (zero area on
///            the ground) and triangles with non-finite coordinates are ignored.
/// A sample on an edge shared by two triangles is interpolated in both and keeps the larger
/// error; it is counted once. Samples are placed where a vertex on them would be stored,
/// float(j*spacingX) and float(i*spacingY), with the height float(h*verticalScale), so a mesh
/// whose vertices sit exactly on samples shows exactly zero error there.
ErrorStats evaluateMeshError(const Heightfield& field, const float* positions, size_t vertexCount,
                             size_t strideFloats, const uint32_t* indices, size_t indexCount,
                             const ErrorOptions& options = {});

} // namespace hexlod
