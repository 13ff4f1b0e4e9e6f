// Refinement data of one cell (paper §5, Fig. 10), made conservative: computed from every
// sample the cell encloses, not from its corners.
#pragma once

#include <cstdint>
#include <limits>

#include "mesh/embedding.h"
#include "field/heightfield.h"
#include "mesh/hex_mesh.h"
#include "field/min_max_pyramid.h"

namespace hexlod {

/// What a cell's drawn triangles depend on: its kind, its own corners and its lattice centre
/// and step. The data of a cell's parent (what a merge would make) uses the same description.
struct CellShape {
    CellKind kind = CellKind::Full;
    int32_t firstVisible = 0;
    LatticePoint center;
    int32_t step = 1;
};

/// What refinement caches per cell (§5.1): 12 bytes.
struct CellError {
    float low = 0, high = 0; // metres (unscaled): lowest and highest of its samples and vertices
    float error = 0;         // metres (unscaled): bound on |sample - drawn surface| under the cell
};

/// The ground rectangle of a cell's own corners (and centre), metres. Cheap: lattice only.
struct Footprint {
    float x0 = 0, x1 = 0, z0 = 0, z1 = 0;
};

/// Cells with at most this many samples under their footprint are scanned sample by sample;
/// larger ones are bounded through the min/max pyramid.
constexpr double kExactScanSamples = 4096.0;

inline bool sameShape(const CellShape& a, const CellShape& b) {
    return a.kind == b.kind && a.firstVisible == b.firstVisible && a.center.q == b.center.q && a.center.r == b.center.r &&
           a.step == b.step;
}

/// The shape of a live cell, and of the cell a merge of it would make.
CellShape shapeOfCell(const HexMesh& mesh, int32_t cell);
CellShape parentShapeOfCell(const HexMesh& mesh, int32_t cell);

Footprint footprintOf(const Heightfield& field, Embedding embedding, const CellShape& shape);
/// The columns and rows of samples a footprint spans, rounded outwards; not clamped to the field.
SampleRect samplesUnder(const Heightfield& field, const Footprint& footprint);

/// The range of slopes of the true surface under a footprint (paper §5's cone of normals, as a
/// box of gradients): dh/dx in [dxLow, dxHigh] and dh/dz in [dzLow, dzHigh] over every
/// triangle of the full-resolution triangulation of the samples there (both diagonals of each
/// sample square, a superset). Unknown (never back-facing) for large cells and for the shifted
/// embedding, whose stored surface is not the samples' triangulation.
struct SlopeBox {
    // Unknown: an empty box (no flag, so a cache entry stays 40 bytes; refinement_cache.h).
    float dxLow = std::numeric_limits<float>::infinity(), dxHigh = -std::numeric_limits<float>::infinity();
    float dzLow = std::numeric_limits<float>::infinity(), dzHigh = -std::numeric_limits<float>::infinity();
    bool known() const { return dxLow <= dxHigh && dzLow <= dzHigh; }
};

SlopeBox slopesUnder(const Heightfield& field, Embedding embedding, const Footprint& footprint);

/// Error bound of a cell against the original samples, each at its true position
/// (x = j * spacingX, z = i * spacingY). Samples outside the field are not considered (the
/// lattice reaches past it).
CellError computeCellError(const Heightfield& field, Embedding embedding, const MinMaxPyramid& pyramid,
                           const CellShape& shape);

} // namespace hexlod
