// The blends that a merge waits for (paper §7), as the refiner sees them: "If a vertex v is to
// be removed, inverse blending is triggered by a merge [...], which [is] finished when the
// vertex has faded out." The refiner asks to fade vertices out, to call a fade off, and whether
// one has finished; how a vertex blends, and the frame clock that moves the blends, belong to
// the implementation (the geomorph blends, class Geomorph; Terrain ticks its clock once per
// LOD update).
#pragma once

#include <cstdint>

#include "mesh/hex_mesh.h"

namespace hexlod {

class VertexFades {
public:
    /// Off: vertices vanish at once, and a merge happens when it is wanted.
    virtual bool enabled() const = 0;
    /// Starts fading out vertex v (one a merge will free) towards the coarser surface between
    /// its parents, from where it is drawn now.
    virtual void blendOut(HexMesh& mesh, int32_t v, const VertexParents& parents) = 0;
    /// Reverses a fade (its merge was called off), from where the vertex is drawn now.
    virtual void cancelBlendOut(HexMesh& mesh, int32_t v) = 0;
    virtual bool blendingOut(const StreamVertex& v) const = 0;
    /// Faded out: freeing the vertex changes nothing on screen.
    virtual bool fadedOut(const StreamVertex& v) const = 0;

protected:
    ~VertexFades() = default; // not owned through this interface
};

} // namespace hexlod
