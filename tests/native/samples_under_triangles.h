// Every sample of a field under each of a mesh's drawn triangles, with its barycentric weights
// there: a brute-force walk over the drawn surface, independent of the refiner's bounds, for the
// tests that check a bound sample by sample.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "field/heightfield.h"
#include "mesh/hex_mesh.h"

namespace hexlod::test {

/// Calls visit(corners, j, i, w) for every sample (column j, row i) inside a drawn triangle
/// (on its edges too: a sample on a shared edge is visited once per triangle), corners the
/// triangle's vertex positions (metres, heights as the mesh stores them) and w[3] the sample's
/// weights. foldOverhang: vertices past the field's edges are first moved onto them, as the
/// shader folds the lattice's overhang. Triangles with no area on the ground are skipped.
template <typename Visit>
void forEachSampleUnderTriangles(const HexMesh& mesh, const Heightfield& field, bool foldOverhang, Visit&& visit) {
    std::vector<uint32_t> tris;
    mesh.appendTriangles(tris);
    const double sx = field.scale().spacingX, sy = field.scale().spacingY;
    const double xMax = (field.width() - 1) * sx, zMax = (field.height() - 1) * sy;
    for (size_t t = 0; t < tris.size(); t += 3) {
        glm::dvec3 v[3];
        for (int32_t k = 0; k < 3; ++k) {
            const glm::vec3 p = mesh.vertexPosition(int32_t(tris[t + size_t(k)]));
            v[k] = foldOverhang ? glm::dvec3(std::clamp(double(p.x), 0.0, xMax), p.y, std::clamp(double(p.z), 0.0, zMax)) : glm::dvec3(p);
        }
        const double area = (v[1].x - v[0].x) * (v[2].z - v[0].z) - (v[2].x - v[0].x) * (v[1].z - v[0].z);
        if (std::abs(area) < 1e-9) continue;
        const int32_t i0 = std::max(0, int32_t(std::floor(std::min({v[0].z, v[1].z, v[2].z}) / sy)));
        const int32_t i1 = std::min(field.height() - 1, int32_t(std::ceil(std::max({v[0].z, v[1].z, v[2].z}) / sy)));
        const int32_t j0 = std::max(0, int32_t(std::floor(std::min({v[0].x, v[1].x, v[2].x}) / sx)));
        const int32_t j1 = std::min(field.width() - 1, int32_t(std::ceil(std::max({v[0].x, v[1].x, v[2].x}) / sx)));
        for (int32_t i = i0; i <= i1; ++i)
            for (int32_t j = j0; j <= j1; ++j) {
                const double x = j * sx, z = i * sy;
                double w[3];
                w[1] = ((x - v[0].x) * (v[2].z - v[0].z) - (v[2].x - v[0].x) * (z - v[0].z)) / area;
                w[2] = ((v[1].x - v[0].x) * (z - v[0].z) - (x - v[0].x) * (v[1].z - v[0].z)) / area;
                w[0] = 1.0 - w[1] - w[2];
                if (w[0] < -1e-9 || w[1] < -1e-9 || w[2] < -1e-9) continue;
                visit(v, j, i, w);
            }
    }
}

} // namespace hexlod::test
