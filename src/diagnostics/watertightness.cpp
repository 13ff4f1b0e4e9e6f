// Watertightness of the drawn triangles (paper §7's fan stream, seen as the GPU assembles it);
// see watertightness.h. Edges are bucketed by their start vertex (no hashing): linear time, and
// the same verdict and message in every build.
#include "diagnostics/watertightness.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace hexlod {

namespace {

constexpr uint32_t kRestart = 0xFFFFFFFFu;

thread_local char message[256];

__attribute__((format(printf, 1, 2))) const char* failure(const char* format, ...) {
    va_list args;
    va_start(args, format);
    std::vsnprintf(message, sizeof(message), format, args);
    va_end(args);
    return message;
}

} // namespace

void assembleTriangles(const uint32_t* indices, size_t count, Primitive primitive, std::vector<uint32_t>& out) {
    uint32_t held[3];
    int32_t n = 0; // vertices since the last restart (a fan's count keeps growing)
    for (size_t k = 0; k < count; ++k) {
        const uint32_t i = indices[k];
        if (i == kRestart) {
            n = 0;
            continue;
        }
        if (primitive == Primitive::Triangles) {
            held[n++] = i;
            if (n == 3) out.insert(out.end(), {held[0], held[1], held[2]}), n = 0;
        } else {
            if (n == 0) held[0] = i;
            else if (n >= 2) out.insert(out.end(), {held[0], held[1], i});
            held[1] = i;
            ++n;
        }
    }
}

WatertightStats checkWatertight(const std::vector<uint32_t>& triangles, const float* positions, size_t vertexCount, size_t strideWords,
                                const std::function<bool(uint32_t)>& live) {
    WatertightStats stats;
    stats.triangles = int64_t(triangles.size() / 3);
    if (triangles.size() % 3 != 0) return stats.error = failure("%zu indices are not whole triangles", triangles.size()), stats;
    if (triangles.empty()) return stats.error = failure("no triangles are drawn"), stats;
    auto at = [&](uint32_t v) { return positions + size_t(v) * strideWords; };

    // Vertices and triangles: valid, live, finite, counter-clockwise seen from +y.
    std::vector<uint8_t> used(vertexCount, 0);
    for (size_t t = 0; t < triangles.size(); t += 3) {
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t v = triangles[t + k];
            if (v >= vertexCount) return stats.error = failure("triangle %zu uses vertex %u of %zu", t / 3, v, vertexCount), stats;
            if (live && !live(v)) return stats.error = failure("triangle %zu uses free vertex slot %u", t / 3, v), stats;
            const float* p = at(v);
            if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
                return stats.error = failure("vertex %u has a non-finite position", v), stats;
            if (!used[v]) used[v] = 1, ++stats.vertices;
        }
        const float *a = at(triangles[t]), *b = at(triangles[t + 1]), *c = at(triangles[t + 2]);
        const double crossY = (double(b[2]) - a[2]) * (double(c[0]) - a[0]) - (double(b[0]) - a[0]) * (double(c[2]) - a[2]);
        if (!(crossY > 0.0))
            return stats.error = failure("triangle %zu (vertices %u, %u, %u) is %s seen from above", t / 3, triangles[t], triangles[t + 1],
                                         triangles[t + 2], crossY == 0.0 ? "degenerate" : "clockwise"),
                   stats;
    }

    // Directed edges by their start vertex (a vertex has a handful): each used once; the ones
    // whose reverse nobody uses are the boundary.
    std::vector<uint32_t> first(vertexCount + 1, 0), to(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t) ++first[triangles[t] + 1];
    for (size_t v = 0; v < vertexCount; ++v) first[v + 1] += first[v];
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (size_t t = 0; t < triangles.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) to[fill[triangles[t + k]]++] = triangles[t + (k + 1) % 3];
    auto hasEdge = [&](uint32_t a, uint32_t b) { return std::find(&to[first[a]], &to[first[a + 1]], b) != &to[first[a + 1]]; };

    // The boundary: one edge out of and one into each boundary vertex, then one loop. A crack or
    // T-junction whose ends lie on the outline (or on another crack) shows as a pinch.
    auto pinch = [&](uint32_t v, const char* what) {
        return failure("a crack or T-junction at vertex %u at (%.3f, %.3f) (x, z metres): it %s two boundary edges (or the surface "
                       "pinches there)", v, double(at(v)[0]), double(at(v)[2]), what);
    };
    constexpr uint32_t kNone = 0xFFFFFFFFu;
    std::vector<uint32_t> next(vertexCount, kNone); // the boundary edge leaving a vertex
    std::vector<uint8_t> ends(vertexCount, 0);
    for (uint32_t a = 0; a < uint32_t(vertexCount); ++a) {
        for (uint32_t k = first[a]; k < first[a + 1]; ++k) {
            const uint32_t b = to[k];
            if (std::find(&to[k + 1], &to[first[a + 1]], b) != &to[first[a + 1]])
                return stats.error = failure("edge %u -> %u is used by two triangles in the same direction (overlap or fold)", a, b), stats;
            if (hasEdge(b, a)) continue;
            ++stats.boundaryEdges;
            if (next[a] != kNone) return stats.error = pinch(a, "starts"), stats;
            if (ends[b]++) return stats.error = pinch(b, "ends"), stats;
            next[a] = b;
        }
    }
    stats.edges = (int64_t(triangles.size()) + stats.boundaryEdges) / 2;
    stats.euler = stats.vertices - stats.edges + stats.triangles;
    std::vector<uint8_t> visited(vertexCount, 0);
    int64_t shortest = stats.boundaryEdges + 1;
    uint32_t shortestStart = 0;
    for (uint32_t start = 0; start < uint32_t(vertexCount); ++start) {
        if (next[start] == kNone || visited[start]) continue;
        ++stats.boundaryLoops;
        int64_t length = 0;
        for (uint32_t v = start; !visited[v]; v = next[v]) {
            visited[v] = 1;
            ++length;
            if (next[next[v]] == kNone)
                return stats.error = failure("the boundary ends at vertex %u: no boundary edge leaves it", next[v]), stats;
        }
        if (length < shortest) shortest = length, shortestStart = start;
    }
    if (stats.boundaryLoops != 1) {
        const uint32_t u = shortestStart, v = next[shortestStart];
        return stats.error = failure("a crack or T-junction: the boundary forms %lld loops, not 1; the shortest (%lld edges) runs from "
                                     "vertex %u at (%.3f, %.3f) to %u at (%.3f, %.3f) (x, z metres)",
                                     (long long)stats.boundaryLoops, (long long)shortest, u, double(at(u)[0]), double(at(u)[2]), v,
                                     double(at(v)[0]), double(at(v)[2])),
               stats;
    }
    if (stats.euler != 1)
        return stats.error = failure("the triangles are not one disc: Euler characteristic %lld (V %lld - E %lld + F %lld), not 1",
                                     (long long)stats.euler, (long long)stats.vertices, (long long)stats.edges, (long long)stats.triangles),
               stats;
    return stats;
}

} // namespace hexlod
