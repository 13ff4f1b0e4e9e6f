// The drawn surface of paper §7 (fans and geomorph blends).
// See drawn_surface.h. Reads the same index slots and the same blend formula as the renderer
// (FanStream's layouts, Geomorph::displayed = shaders/terrain.vert).
#include "stream/drawn_surface.h"

#include <algorithm>
#include <cmath>

namespace hexlod {

namespace {

// Height of triangle (a, b, c) over (x, z) by barycentric weights in the ground plane; false
// when the point is outside it or the triangle is degenerate on the ground.
bool heightInTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, double x, double z, double& h) {
    const double d = double(b.x - a.x) * double(c.z - a.z) - double(c.x - a.x) * double(b.z - a.z);
    if (d == 0.0) return false;
    const double u = ((x - a.x) * double(c.z - a.z) - double(c.x - a.x) * (z - a.z)) / d;
    const double v = (double(b.x - a.x) * (z - a.z) - (x - a.x) * double(b.z - a.z)) / d;
    constexpr double kEdge = -1e-9; // a point on a shared edge belongs to both triangles
    if (u < kEdge || v < kEdge || u + v > 1.0 - kEdge) return false;
    h = double(a.y) + u * double(b.y - a.y) + v * double(c.y - a.y);
    return true;
}

} // namespace

bool drawnHeightAt(const Heightfield& field, const HexMesh& mesh, const FanStream& stream, const Geomorph& morph, double x, double z,
                   float& height) {
    const std::vector<uint32_t>& indices = stream.indices();
    const int32_t slot = stream.slotSize();
    const bool fans = stream.layout() == IndexLayout::Fans;
    const StreamVertex* pool = mesh.vertexData();
    // A cell's vertices lie within 2 * step columns (plus the half sample of shifted rows) and
    // rows of its first vertex (a semi-hexagon's first is a corner of its long edge); blends
    // start on the coarser surface just under a vertex.
    const double spacing = std::max(field.scale().spacingX, field.scale().spacingY);
    bool found = false;
    double best = 0.0;
    glm::vec3 p[18];
    for (size_t first = 0; first + size_t(slot) <= indices.size(); first += size_t(slot)) {
        const uint32_t* s = &indices[first];
        if (s[0] == kRestartIndex) continue; // a free record
        const glm::vec3& first0 = pool[s[0]].position;
        const double reach = double(2 * mesh.cellStep(int32_t(first / size_t(slot))) + 1) * spacing;
        if (std::abs(x - first0.x) > reach || std::abs(z - first0.z) > reach) continue;
        // The slot's vertices as drawn, and their ground rectangle: most fans are rejected here.
        int32_t n = 0;
        float x0 = 1e30f, x1 = -1e30f, z0 = 1e30f, z1 = -1e30f;
        while (n < slot && s[n] != kRestartIndex) {
            p[n] = morph.displayed(pool[s[n]]);
            x0 = std::min(x0, p[n].x), x1 = std::max(x1, p[n].x);
            z0 = std::min(z0, p[n].z), z1 = std::max(z1, p[n].z);
            ++n;
        }
        if (x < x0 || x > x1 || z < z0 || z > z1) continue;
        const int32_t triangles = fans ? n - 2 : n / 3;
        for (int32_t t = 0; t < triangles; ++t) {
            const glm::vec3& a = fans ? p[0] : p[3 * t];
            const glm::vec3& b = fans ? p[t + 1] : p[3 * t + 1];
            const glm::vec3& c = fans ? p[t + 2] : p[3 * t + 2];
            double h;
            if (heightInTriangle(a, b, c, x, z, h) && (!found || h > best)) {
                best = h;
                found = true;
            }
        }
    }
    if (found) height = float(best);
    return found;
}

} // namespace hexlod
