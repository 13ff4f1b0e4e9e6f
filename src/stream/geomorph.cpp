// Geomorph blends (paper §7); see geomorph.h.
#include "stream/geomorph.h"

namespace hexlod {

void Geomorph::coarserWeights(const HexMesh& mesh, int32_t v, const VertexParents& parents, float w[3]) {
    w[0] = w[1] = 0.5f, w[2] = 0.0f;
    const int32_t c = parents.across;
    if (c == kNone || !mesh.isVertexLive(c)) return;
    // Barycentric coordinates in the ground plane: p = a + s (b - a) + t (c - a).
    const glm::dvec3 a(mesh.vertexPosition(parents.a)), b(mesh.vertexPosition(parents.b)), cc(mesh.vertexPosition(c)),
        p(mesh.vertexPosition(v));
    const double e1x = b.x - a.x, e1z = b.z - a.z, e2x = cc.x - a.x, e2z = cc.z - a.z, px = p.x - a.x, pz = p.z - a.z;
    const double det = e1x * e2z - e1z * e2x;
    if (det == 0.0) return;
    const double s = (px * e2z - pz * e2x) / det, t = (e1x * pz - e1z * px) / det;
    w[0] = float(1.0 - s - t), w[1] = float(s), w[2] = float(t);
}

float Geomorph::coarserHeightNow(const HexMesh& mesh, int32_t v, const VertexParents& parents) const {
    if (parents.a == kNone || parents.b == kNone) return mesh.vertexPosition(v).y;
    return coarserSurface(mesh, v, parents, [&](int32_t u) { return displayed(mesh.streamVertex(u)); }).y;
}

void Geomorph::blendIn(HexMesh& mesh, int32_t v, const VertexParents& parents) {
    StreamVertex& sv = mesh.streamVertex(v);
    sv.morphFromHeight = coarserHeightNow(mesh, v, parents);
    sv.morphKey = enabled() ? float(frame_) + 1.0f : 0.0f; // weight 0 in the frame it appears
    changed_.push_back(v);
}

void Geomorph::blendToNewHeight(HexMesh& mesh, int32_t v, float shown) {
    StreamVertex& sv = mesh.streamVertex(v);
    if (sv.morphKey < 0.0f) return;
    sv.morphFromHeight = shown;
    sv.morphKey = enabled() ? float(frame_) + 1.0f : 0.0f;
    changed_.push_back(v);
}

void Geomorph::blendOut(HexMesh& mesh, int32_t v, const VertexParents& parents) {
    StreamVertex& sv = mesh.streamVertex(v);
    if (!enabled() || sv.morphKey < 0.0f) return;
    const float w = weight(sv);
    // A vertex at rest fades to the parent midpoint as drawn now; one still blending in
    // reverses along its own path, so nothing jumps.
    if (w == 1.0f) sv.morphFromHeight = coarserHeightNow(mesh, v, parents);
    const float start = float(frame_) - (1.0f - w) * float(frames_); // weight(now) == w
    sv.morphKey = -(start + 1.0f);
    changed_.push_back(v);
}

void Geomorph::cancelBlendOut(HexMesh& mesh, int32_t v) {
    StreamVertex& sv = mesh.streamVertex(v);
    if (sv.morphKey >= 0.0f) return;
    const float w = weight(sv);
    const float start = float(frame_) - w * float(frames_);
    sv.morphKey = start + 1.0f;
    changed_.push_back(v);
}

} // namespace hexlod
