#include "grid_mesh.h"

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace hexlod {
namespace {

// Sample indices 0, step, 2*step, ..., and always the last one.
std::vector<int32_t> gridLines(int32_t samples, int32_t step) {
    std::vector<int32_t> lines;
    for (int32_t k = 0; k < samples - 1; k += step) lines.push_back(k);
    lines.push_back(samples - 1);
    return lines;
}

} // namespace

bool buildGridMesh(const Heightfield& field, int32_t maxCellsPerSide, float verticalScale,
                   GridMesh& mesh) {
    mesh.vertices.clear();
    mesh.indices.clear();
    if (maxCellsPerSide < 1) return false;
    const int32_t longest = std::max(field.width(), field.height()) - 1;
    const int32_t step = std::max(1, (longest + maxCellsPerSide - 1) / maxCellsPerSide);
    const std::vector<int32_t> cols = gridLines(field.width(), step);
    const std::vector<int32_t> rows = gridLines(field.height(), step);
    const size_t nc = cols.size(), nr = rows.size();
    const HeightfieldScale& scale = field.scale();

    mesh.vertices.resize(nc * nr);
    for (size_t r = 0; r < nr; ++r) {
        for (size_t c = 0; c < nc; ++c) {
            MeshVertex& v = mesh.vertices[r * nc + c];
            v.x = float(cols[c] * scale.spacingX);
            v.z = float(rows[r] * scale.spacingY);
            v.y = field.heightAt(cols[c], rows[r]) * verticalScale;
        }
    }
    // Normal from central differences over the neighbouring grid vertices (one-sided at the
    // border): the gradient of the surface that is actually drawn, not of the full field.
    for (size_t r = 0; r < nr; ++r) {
        for (size_t c = 0; c < nc; ++c) {
            const MeshVertex& w = mesh.vertices[r * nc + (c > 0 ? c - 1 : c)];
            const MeshVertex& e = mesh.vertices[r * nc + (c + 1 < nc ? c + 1 : c)];
            const MeshVertex& n = mesh.vertices[(r > 0 ? r - 1 : r) * nc + c];
            const MeshVertex& s = mesh.vertices[(r + 1 < nr ? r + 1 : r) * nc + c];
            const float dydx = (e.y - w.y) / (e.x - w.x);
            const float dydz = (s.y - n.y) / (s.z - n.z);
            const glm::vec3 normal = glm::normalize(glm::vec3(-dydx, 1.0f, -dydz));
            MeshVertex& v = mesh.vertices[r * nc + c];
            v.nx = normal.x;
            v.ny = normal.y;
            v.nz = normal.z;
        }
    }
    mesh.indices.reserve((nc - 1) * (nr - 1) * 6);
    for (size_t r = 0; r + 1 < nr; ++r) {
        for (size_t c = 0; c + 1 < nc; ++c) {
            const uint32_t a = uint32_t(r * nc + c), b = a + 1;
            const uint32_t d = uint32_t((r + 1) * nc + c), e = d + 1;
            // x east, z south, y up: (a, d, b) turns counter-clockwise seen from above.
            mesh.indices.insert(mesh.indices.end(), {a, d, b, b, d, e});
        }
    }
    return true;
}

} // namespace hexlod
