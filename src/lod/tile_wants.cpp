// The tiles to fetch; see tile_wants.h.
#include "lod/tile_wants.h"

#include <algorithm>
#include <cmath>

#include "lod/cell_bounds.h"

namespace hexlod {

namespace {

// The samples under a footprint that lie in the field.
SampleRect fieldSamplesUnder(const Heightfield& field, const Footprint& f) {
    const SampleRect r = samplesUnder(field, f);
    return {std::max(0, r.j0), std::max(0, r.i0), std::min(field.width() - 1, r.j1), std::min(field.height() - 1, r.i1)};
}

} // namespace

void TileWants::want(const SampleTiles& tiles, int32_t level, int32_t tx, int32_t ty, float priority) {
    if (tiles.present(level, tx, ty)) return;
    Listed& listed = listed_[size_t(level)].at(tx, ty);
    if (listed.stamp == now_) {
        TileWant& w = wants_[size_t(listed.index)];
        w.priority = std::max(w.priority, priority);
        return;
    }
    listed = {now_, int32_t(wants_.size())};
    wants_.push_back({level, tx, ty, priority});
}

bool TileWants::begin(const Heightfield& field) {
    wants_.clear();
    const SampleTiles* tiles = field.tiles();
    if (!tiles) return false;
    if (listed_.size() != size_t(tiles->levelCount())) {
        listed_.assign(size_t(tiles->levelCount()), {});
        for (int32_t k = 0; k < tiles->levelCount(); ++k) listed_[size_t(k)].reset(tiles->level(k).tilesAcross, tiles->level(k).tilesDown, Listed{});
        now_ = 0;
    }
    if (++now_ == 0) { // the stamps wrapped: start them again
        for (auto& grid : listed_) grid.fillWritten(Listed{});
        now_ = 1;
    }
    return true;
}

const std::vector<TileWant>& TileWants::collect(const HexMesh& mesh, const Heightfield& field, const std::vector<float>& starved) {
    if (!begin(field)) return wants_;
    const SampleTiles* tiles = field.tiles();
    const int32_t cells = std::min(int32_t(starved.size()), mesh.cellCapacity());
    for (int32_t c = 0; c < cells; ++c) {
        const float priority = starved[size_t(c)];
        if (!(priority > 0.0f) || !mesh.isLive(c)) continue;
        const CellShape shape = shapeOfCell(mesh, c);
        const Footprint f = footprintOf(field, mesh.embedding(), shape);
        SampleRect rect = fieldSamplesUnder(field, f);
        if (rect.empty()) continue;
        float detail;
        const int32_t now = tiles->levelIn(rect, detail);
        if (now == 0) continue;
        // The coarsest level fine enough for the children (their vertices step / 2 samples
        // apart); at least one finer than now.
        int32_t target = now - 1;
        while (target > 0) {
            const TileLevel& l = tiles->level(target);
            if (std::max(l.scaleX, l.scaleY) <= 0.5 * shape.step) break;
            --target;
        }
        // Heights come from a level over whole regions (full-resolution tiles): every tile of
        // the target level that those regions reach.
        const int32_t rw = tiles->regionWidth(), rh = tiles->regionHeight();
        rect.j0 = rect.j0 / rw * rw, rect.i0 = rect.i0 / rh * rh;
        rect.j1 = std::min(field.width() - 1, (rect.j1 / rw + 1) * rw - 1);
        rect.i1 = std::min(field.height() - 1, (rect.i1 / rh + 1) * rh - 1);
        int32_t tx0, ty0, tx1, ty1;
        tiles->tilesCovering(target, rect, tx0, ty0, tx1, ty1);
        for (int32_t ty = ty0; ty <= ty1; ++ty)
            for (int32_t tx = tx0; tx <= tx1; ++tx) want(*tiles, target, tx, ty, priority);
    }
    auto moreNeeded = [](const TileWant& a, const TileWant& b) {
        if (a.priority != b.priority) return a.priority > b.priority;
        if (a.level != b.level) return a.level > b.level; // coarser first: it serves more cells
        return a.ty != b.ty ? a.ty < b.ty : a.tx < b.tx;
    };
    if (wants_.size() > size_t(kMaxWants)) {
        std::nth_element(wants_.begin(), wants_.begin() + kMaxWants, wants_.end(), moreNeeded);
        wants_.resize(size_t(kMaxWants));
    }
    std::sort(wants_.begin(), wants_.end(), moreNeeded);
    return wants_;
}

const std::vector<TileWant>& TileWants::collectInUse(const HexMesh& mesh, const Heightfield& field) {
    if (!begin(field)) return wants_;
    const SampleTiles* tiles = field.tiles();
    for (int32_t c = 0; c < mesh.cellCapacity(); ++c) {
        if (!mesh.isLive(c)) continue;
        const CellShape shape = shapeOfCell(mesh, c);
        const Footprint f = footprintOf(field, mesh.embedding(), shape);
        const SampleRect rect = fieldSamplesUnder(field, f);
        if (rect.empty()) continue;
        // A cell of step s stands on samples at most s apart (a coarser level would have held
        // its parent back): the levels of spacing s down to s / 4, the nearest two.
        for (int32_t l = 0; l < tiles->coarsest(); ++l) {
            const TileLevel& level = tiles->level(l);
            const double spacing = std::max(level.scaleX, level.scaleY);
            if (spacing > shape.step * (1.0 + 1e-9)) break;
            if (spacing < 0.25 * shape.step) continue;
            int32_t tx0, ty0, tx1, ty1;
            tiles->tilesCovering(l, rect, tx0, ty0, tx1, ty1);
            for (int32_t ty = ty0; ty <= ty1; ++ty)
                for (int32_t tx = tx0; tx <= tx1; ++tx) {
                    if (!tiles->present(l, tx, ty)) continue;
                    Listed& listed = listed_[size_t(l)].at(tx, ty);
                    if (listed.stamp == now_) continue;
                    listed = {now_, int32_t(wants_.size())};
                    wants_.push_back({l, tx, ty, 0.0f});
                }
        }
    }
    return wants_;
}

size_t TileWants::memoryBytes() const {
    size_t bytes = wants_.capacity() * sizeof(TileWant);
    for (const auto& grid : listed_) bytes += grid.memoryBytes();
    return bytes;
}

} // namespace hexlod
