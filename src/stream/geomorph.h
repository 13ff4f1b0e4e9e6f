// Geomorph: the blends that hide popping (paper §7). "When splitting an edge of a hexagon, the
// end points of the edge are assigned to the new vertex together with a stop value n frames
// ahead. Until the frame counter has reached the stop value, the position of a newly inserted
// vertex v is linearly interpolated between the edge's mid point in space and the height field
// value of v. If a vertex v is to be removed, inverse blending is triggered by a merge- or
// inverse join-operation, which are finished when the vertex has faded out."
//
// The blend lives in each StreamVertex (morphFromHeight, morphKey) and is evaluated in the vertex
// shader from the frame counter, so a blending vertex is written once, not every frame. The
// weight formula below is the shader's (shaders/terrain.vert), in the same float arithmetic.
// The start is the coarser surface under the vertex as drawn in that frame (the corners of the
// coarser triangle may still be blending themselves): in the paper's embedding the midpoint of
// the parent edge in space, in the exact-sample embedding (where a vertex may sit up to half a
// sample off its parent edge) the point of the parent triangle straight below or above it, so
// the vertex blends vertically, as the paper's does. Either way only the height moves (the
// midpoint of the parent edge lies over the vertex in the paper's embedding), so a blend keeps
// just its start height.
// The blend is tied to frames, so it is deterministic under a fixed frame clock.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "lod/vertex_fades.h"
#include "mesh/hex_mesh.h"

namespace hexlod {

// The refiner's merges wait for these blends through VertexFades (lod/vertex_fades.h).
class Geomorph final : public VertexFades {
public:
    /// The clock starts here so that a reversed blend's start frame (up to kMaxFrames in the
    /// past) stays positive, which its sign encoding needs.
    static constexpr uint32_t kFirstFrame = 1024;
    static constexpr int32_t kMaxFrames = 1000;

    /// Frames a blend takes; 0 turns geomorphing off (vertices appear and vanish at once).
    void setFrames(int32_t frames) { frames_ = std::clamp(frames, 0, kMaxFrames); }
    int32_t frames() const { return frames_; }
    bool enabled() const override { return frames_ > 0; }

    /// The frame counter: one tick per LOD update, i.e. per drawn frame. Keys and the shader's
    /// uniform are floats, exact to 2^24 frames (77 hours at 60 fps); past that, blends still
    /// end (the weight clamps) but step less evenly.
    uint32_t frame() const { return frame_; }
    void advance() { ++frame_; }
    void resetClock() { frame_ = kFirstFrame; }

    /// How far a vertex is towards its true position this frame: 1 there, 0 at its start.
    float weight(const StreamVertex& v) const {
        if (v.morphKey == 0.0f || frames_ == 0) return 1.0f;
        const float start = v.morphKey > 0.0f ? v.morphKey - 1.0f : -v.morphKey - 1.0f;
        const float t = std::clamp((float(frame_) - start) / float(frames_), 0.0f, 1.0f);
        return v.morphKey > 0.0f ? t : 1.0f - t;
    }
    /// Where the vertex is drawn this frame (unscaled heights).
    glm::vec3 displayed(const StreamVertex& v) const {
        const float w = weight(v);
        return {v.position.x, v.morphFromHeight + (v.position.y - v.morphFromHeight) * w, v.position.z};
    }

    /// Weights of a vertex over its parents a, b and across (VertexParents) such that their
    /// weighted ground-plane position is the vertex's: the coarser surface under it is the same
    /// weighted sum of their positions. (0.5, 0.5, 0) on the parent edge or without across.
    static void coarserWeights(const HexMesh& mesh, int32_t v, const VertexParents& parents, float w[3]);
    /// The coarser surface under vertex v, with `drawn(u)` where vertex u is drawn. Needs a and b.
    template <typename Drawn>
    static glm::vec3 coarserSurface(const HexMesh& mesh, int32_t v, const VertexParents& parents, Drawn&& drawn) {
        float w[3];
        coarserWeights(mesh, v, parents, w);
        glm::vec3 p = w[0] * drawn(parents.a) + w[1] * drawn(parents.b);
        if (w[2] != 0.0f) p += w[2] * drawn(parents.across);
        return p;
    }

    /// A vertex the mesh just created, with its parents: blends in from the coarser surface
    /// under it as drawn now. With geomorphing off it appears at once; morphFromHeight still
    /// records the start (the popping meter measures the jump from there).
    void blendIn(HexMesh& mesh, int32_t v, const VertexParents& parents);
    /// A vertex a merge will free: blends back to the coarser surface under it, continuing
    /// from where it is drawn now. Not yet blending out; without parents a and b it has no
    /// coarser surface to go to (a base vertex) and stays.
    void blendOut(HexMesh& mesh, int32_t v, const VertexParents& parents) override;
    /// A vertex whose true height changed under it (a tiled field's finer samples came, or
    /// went): it blends from where it is drawn now, `shown`, to its new position, as a new vertex
    /// blends in. One that is fading out keeps fading (its merge is under way).
    void blendToNewHeight(HexMesh& mesh, int32_t v, float shown);
    /// Reverses a blend-out (the merge was called off), continuing from where it is drawn.
    void cancelBlendOut(HexMesh& mesh, int32_t v) override;
    bool blendingOut(const StreamVertex& v) const override { return v.morphKey < 0.0f; }
    /// Faded out: drawn at the parent midpoint, so freeing it changes nothing on screen.
    bool fadedOut(const StreamVertex& v) const override { return v.morphKey < 0.0f && weight(v) == 0.0f; }

    /// Vertices whose blend changed since the last take (the renderer re-uploads them).
    std::vector<int32_t>& changedVertices() { return changed_; }

private:
    float coarserHeightNow(const HexMesh& mesh, int32_t v, const VertexParents& parents) const;

    int32_t frames_ = 0;
    uint32_t frame_ = kFirstFrame;
    std::vector<int32_t> changed_;
};

} // namespace hexlod
