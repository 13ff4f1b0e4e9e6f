#include "fan_stream.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace hexlod {

namespace {

// Appends the fan of one cell (see fan_stream.h), closed by the restart index.
void appendFan(const HexMesh& mesh, const Hexagon& h, std::vector<uint32_t>& out) {
    const int32_t* v = h.vertex;
    if (h.kind == CellKind::Full) {
        for (int32_t slot = 0; slot <= 7; ++slot) out.push_back(uint32_t(v[slot]));
    } else if (h.kind == CellKind::BoundarySemi) {
        out.push_back(uint32_t(v[0]));
        for (int32_t i = 0; i < 4; ++i) out.push_back(uint32_t(v[wrapSlot(h.firstVisible + i)]));
    } else {
        int32_t slots[4];
        mesh.semiFanSlots(h, slots); // the fixed rule for §7's "arbitrary corner"
        for (int32_t slot : slots) out.push_back(uint32_t(v[slot]));
    }
    out.push_back(kRestartIndex);
}

} // namespace

void buildFanStream(const HexMesh& mesh, float verticalScale, FanStream& stream) {
    stream.indices.clear();
    stream.outline.clear();
    if (!stream.withOutline) stream.outline.shrink_to_fit(); // its memory only while it is shown
    stream.levelOffsets.clear();
    for (int32_t level = 0; level <= mesh.maxLevel(); ++level) {
        stream.levelOffsets.push_back(int32_t(stream.indices.size()));
        for (int32_t c = mesh.firstOfLevel(level); c != kNone; c = mesh.nextInLevel(c)) {
            const Hexagon& h = mesh.cell(c);
            appendFan(mesh, h, stream.indices);
            if (!stream.withOutline) continue;
            // Outline: each cell edge once, from the cell with the lower index (or alone).
            for (int32_t slot = 1; slot <= 6; ++slot) {
                if (h.vertex[slot] == kNone) continue;
                const int32_t e = makeEdge(c, slot);
                const int32_t o = h.opposite[slot - 1];
                if (o != kNone && hexIdx(o) < c) continue;
                stream.outline.push_back(uint32_t(mesh.edgeStart(e)));
                stream.outline.push_back(uint32_t(mesh.edgeEnd(e)));
            }
        }
    }
    stream.levelOffsets.push_back(int32_t(stream.indices.size()));

    // §7: normals averaged from the adjacent triangles of the current mesh (area-weighted
    // sums of face normals, accumulated in the vertices' own normal slots), not taken from
    // the full-resolution field.
    const int32_t count = mesh.vertexCapacity();
    stream.vertexCount = count;
    stream.vertices.resize(size_t(count) * kFloatsPerVertex);
    float* vertices = stream.vertices.data();
    for (int32_t v = 0; v < count; ++v) {
        float* out = vertices + size_t(v) * kFloatsPerVertex;
        const glm::vec3& p = mesh.vertexPosition(v);
        out[0] = p.x, out[1] = p.y * verticalScale, out[2] = p.z;
        out[3] = out[4] = out[5] = 0.0f;
    }
    auto position = [&](uint32_t v) {
        const float* p = vertices + size_t(v) * kFloatsPerVertex;
        return glm::vec3(p[0], p[1], p[2]);
    };
    auto addTriangle = [&](uint32_t a, uint32_t b, uint32_t c) {
        const glm::vec3 n = glm::cross(position(b) - position(a), position(c) - position(a));
        for (uint32_t v : {a, b, c})
            for (int k = 0; k < 3; ++k) vertices[size_t(v) * kFloatsPerVertex + 3 + size_t(k)] += n[k];
    };
    const std::vector<uint32_t>& idx = stream.indices;
    for (size_t start = 0; start < idx.size();) {
        size_t end = start;
        while (idx[end] != kRestartIndex) ++end;
        for (size_t k = start + 1; k + 1 < end; ++k) addTriangle(idx[start], idx[k], idx[k + 1]);
        start = end + 1;
    }
    for (int32_t v = 0; v < count; ++v) {
        float* out = vertices + size_t(v) * kFloatsPerVertex;
        if (!mesh.isVertexLive(v)) {
            std::fill(out, out + kFloatsPerVertex, 0.0f);
            continue;
        }
        glm::vec3 n(out[3], out[4], out[5]);
        // Counter-clockwise triangles seen from +y have normals with y > 0 in this frame.
        const float length = glm::length(n);
        n = length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
        out[3] = n.x, out[4] = n.y, out[5] = n.z;
    }
}

} // namespace hexlod
