// The surface as the renderer draws it this frame: the triangles of the fan stream (paper §7)
// with every vertex where its geomorph blend puts it. The walk camera stands on it, so that
// the eye never dips under what is on screen while the mesh refines or coarsens.
#pragma once

#include "stream/fan_stream.h"
#include "stream/geomorph.h"
#include "field/heightfield.h"
#include "mesh/hex_mesh.h"

namespace hexlod {

/// Height in metres (unscaled) of the drawn surface at ground position (x, z) metres: the
/// highest drawn triangle over that point (triangles meet at shared edges; taking the highest
/// keeps a point on an edge safe). Returns false when no drawn triangle covers the point.
/// A scan over every index slot of the stream; a cell whose first vertex lies farther than its
/// reach from the point costs one read: O(cells), well under a millisecond for 100k triangles.
bool drawnHeightAt(const Heightfield& field, const HexMesh& mesh, const FanStream& stream, const Geomorph& morph, double x, double z,
                   float& height);

} // namespace hexlod
