// Samples that arrive by tiles; see sample_tiles.h.
#include "field/sample_tiles.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <type_traits>

namespace hexlod {

namespace {

// Calls f with the tile's samples as their type (a pointer), so that whole-tile passes read
// them without a branch per sample.
template <typename F>
void withSamples(SampleType type, uint8_t* bytes, F&& f) {
    switch (type) {
        case SampleType::U8: f(bytes); break;
        case SampleType::U16: f(reinterpret_cast<uint16_t*>(bytes)); break;
        case SampleType::I16: f(reinterpret_cast<int16_t*>(bytes)); break;
        case SampleType::F32: f(reinterpret_cast<float*>(bytes)); break;
    }
}

// Bit k of a tile's no-data marks (slotMissing_).
bool marked(const std::vector<uint8_t>& bits, size_t k) { return (bits[k >> 3] >> (k & 7)) & 1; }

} // namespace

void SampleRect::add(const SampleRect& r) {
    if (r.empty()) return;
    if (empty()) {
        *this = r;
        return;
    }
    j0 = std::min(j0, r.j0), i0 = std::min(i0, r.i0), j1 = std::max(j1, r.j1), i1 = std::max(i1, r.i1);
}

const char* SampleTiles::init(int32_t width, int32_t height, SampleType type, int32_t levels, const int32_t* dims) {
    if (levels < 1 || levels > kMaxLevels) return "a tiled field needs 1 to 24 levels";
    if (!dims) return "the levels' sizes are missing";
    width_ = width, height_ = height, type_ = type, bytesPerSample_ = hexlod::sampleBytes(type);
    levels_.clear();
    size_t largestTile = 0;
    for (int32_t k = 0; k < levels; ++k) {
        TileLevel l;
        l.width = dims[4 * k], l.height = dims[4 * k + 1], l.tileWidth = dims[4 * k + 2], l.tileHeight = dims[4 * k + 3];
        if (l.width < 1 || l.height < 1 || l.tileWidth < 1 || l.tileHeight < 1 || l.tileWidth > 4096 || l.tileHeight > 4096)
            return "a level needs a positive size and tiles of 1 to 4096 samples a side";
        if (k == 0 && (l.width != width || l.height != height)) return "level 0 must be the full resolution";
        if (k > 0 && (l.width > levels_.back().width || l.height > levels_.back().height ||
                      (l.width == levels_.back().width && l.height == levels_.back().height)))
            return "each level must be coarser than the one before";
        l.tilesAcross = (l.width + l.tileWidth - 1) / l.tileWidth;
        l.tilesDown = (l.height + l.tileHeight - 1) / l.tileHeight;
        if (int64_t(l.tilesAcross) * l.tilesDown > kMaxTilesPerLevel) return "a level has more than 2^26 tiles: the file needs larger tiles";
        l.scaleX = double(width) / l.width, l.scaleY = double(height) / l.height;
        l.tiles.reset(l.tilesAcross, l.tilesDown, TileState{});
        largestTile = std::max(largestTile, size_t(l.tileWidth) * size_t(l.tileHeight));
        levels_.push_back(std::move(l));
    }
    slotBytes_ = largestTile * bytesPerSample_;
    slots_.clear(), slotOwner_.clear(), slotMissing_.clear(), freeSlots_.clear(), heldSlots_ = 0;
    const TileLevel& finest = levels_[0];
    int32_t group = 1; // full-resolution tiles a region side
    while (((int64_t(finest.tilesAcross) + group - 1) / group) * ((int64_t(finest.tilesDown) + group - 1) / group) > kMaxRegions) group *= 2;
    regionWidth_ = finest.tileWidth * group, regionHeight_ = finest.tileHeight * group;
    regionsAcross_ = (finest.tilesAcross + group - 1) / group, regionsDown_ = (finest.tilesDown + group - 1) / group;
    regionLevel_.assign(size_t(regionsAcross_) * size_t(regionsDown_), uint8_t(coarsest()));
    regionDetail_.assign(regionLevel_.size(), 0.0f);
    hasFill_ = false, voidsAsPits_ = false, fillRaw_ = 0.0, missing_ = 0;
    hasRange_ = false, rangeLow_ = rangeHigh_ = 0.0;
    return nullptr;
}

double SampleTiles::rawIn(int32_t slot, size_t k) const {
    const uint8_t* bytes = slots_[size_t(slot)].get();
    switch (type_) {
        case SampleType::U8: return bytes[k];
        case SampleType::U16: return reinterpret_cast<const uint16_t*>(bytes)[k];
        case SampleType::I16: return reinterpret_cast<const int16_t*>(bytes)[k];
        case SampleType::F32: return reinterpret_cast<const float*>(bytes)[k];
    }
    return 0.0;
}

double SampleTiles::rawAtLevel(const TileLevel& l, int32_t u, int32_t v) const {
    const int32_t tx = u / l.tileWidth, ty = v / l.tileHeight;
    const int32_t slot = l.tiles.get(tx, ty).slot;
    return rawIn(slot, size_t(v - ty * l.tileHeight) * size_t(l.tileWidth) + size_t(u - tx * l.tileWidth));
}

SampleTiles::BlendCorners SampleTiles::blendCorners(const TileLevel& l, int32_t j, int32_t i) const {
    const double u = std::clamp((j + 0.5) / l.scaleX - 0.5, 0.0, double(l.width - 1));
    const double v = std::clamp((i + 0.5) / l.scaleY - 0.5, 0.0, double(l.height - 1));
    const int32_t u0 = int32_t(u), v0 = int32_t(v);
    return {u0, v0, std::min(u0 + 1, l.width - 1), std::min(v0 + 1, l.height - 1), u - u0, v - v0};
}

float SampleTiles::blended(int32_t level, int32_t j, int32_t i) const {
    const TileLevel& l = levels_[size_t(level)];
    const BlendCorners b = blendCorners(l, j, i);
    const double top = double(toMetres(rawAtLevel(l, b.u0, b.v0))) * (1.0 - b.fu) + double(toMetres(rawAtLevel(l, b.u1, b.v0))) * b.fu;
    const double bottom = double(toMetres(rawAtLevel(l, b.u0, b.v1))) * (1.0 - b.fu) + double(toMetres(rawAtLevel(l, b.u1, b.v1))) * b.fu;
    return float(top * (1.0 - b.fv) + bottom * b.fv);
}

bool SampleTiles::missingAtLevel(const TileLevel& l, int32_t u, int32_t v) const {
    const int32_t tx = u / l.tileWidth, ty = v / l.tileHeight;
    const std::vector<uint8_t>& bits = slotMissing_[size_t(l.tiles.get(tx, ty).slot)];
    if (bits.empty()) return false;
    const size_t k = size_t(v - ty * l.tileHeight) * size_t(l.tileWidth) + size_t(u - tx * l.tileWidth);
    return marked(bits, k);
}

bool SampleTiles::missing(int32_t j, int32_t i) const {
    if (missing_ == 0) return false;
    const int32_t level = regionLevel_[regionOf(j / regionWidth_, i / regionHeight_)];
    const TileLevel& l = levels_[size_t(level)];
    if (level == 0) return missingAtLevel(l, j, i);
    const BlendCorners b = blendCorners(l, j, i);
    double weight = 0.0; // of the missing corners
    if (missingAtLevel(l, b.u0, b.v0)) weight += (1.0 - b.fu) * (1.0 - b.fv);
    if (missingAtLevel(l, b.u1, b.v0)) weight += b.fu * (1.0 - b.fv);
    if (missingAtLevel(l, b.u0, b.v1)) weight += (1.0 - b.fu) * b.fv;
    if (missingAtLevel(l, b.u1, b.v1)) weight += b.fu * b.fv;
    return weight >= 0.5;
}

void SampleTiles::samplesFor(int32_t level, const SampleRect& r, int32_t& u0, int32_t& v0, int32_t& u1, int32_t& v1) const {
    const TileLevel& l = levels_[size_t(level)];
    if (level == 0) {
        u0 = std::max(r.j0, 0), v0 = std::max(r.i0, 0), u1 = std::min(r.j1, l.width - 1), v1 = std::min(r.i1, l.height - 1);
        return;
    }
    u0 = std::clamp(int32_t(std::floor((r.j0 + 0.5) / l.scaleX - 0.5)), 0, l.width - 1);
    v0 = std::clamp(int32_t(std::floor((r.i0 + 0.5) / l.scaleY - 0.5)), 0, l.height - 1);
    u1 = std::clamp(int32_t(std::ceil((r.j1 + 0.5) / l.scaleX - 0.5)), 0, l.width - 1);
    v1 = std::clamp(int32_t(std::ceil((r.i1 + 0.5) / l.scaleY - 0.5)), 0, l.height - 1);
}

void SampleTiles::tilesCovering(int32_t level, const SampleRect& rect, int32_t& tx0, int32_t& ty0, int32_t& tx1, int32_t& ty1) const {
    int32_t u0, v0, u1, v1;
    samplesFor(level, rect, u0, v0, u1, v1);
    const TileLevel& l = levels_[size_t(level)];
    tx0 = u0 / l.tileWidth, ty0 = v0 / l.tileHeight, tx1 = u1 / l.tileWidth, ty1 = v1 / l.tileHeight;
}

SampleRect SampleTiles::regionRect(int32_t rx, int32_t ry) const {
    return {rx * regionWidth_, ry * regionHeight_, std::min((rx + 1) * regionWidth_, width_) - 1,
            std::min((ry + 1) * regionHeight_, height_) - 1};
}

SampleRect SampleTiles::tileRect(int32_t level, int32_t tx, int32_t ty) const {
    const TileLevel& l = levels_[size_t(level)];
    // Its samples reach the full-resolution samples within one of its spacings of them.
    const double x0 = (tx * l.tileWidth - 1 + 0.5) * l.scaleX - 0.5, x1 = ((tx + 1) * l.tileWidth + 0.5) * l.scaleX - 0.5;
    const double y0 = (ty * l.tileHeight - 1 + 0.5) * l.scaleY - 0.5, y1 = ((ty + 1) * l.tileHeight + 0.5) * l.scaleY - 0.5;
    return {std::max(0, int32_t(std::floor(x0))), std::max(0, int32_t(std::floor(y0))), std::min(width_ - 1, int32_t(std::ceil(x1))),
            std::min(height_ - 1, int32_t(std::ceil(y1)))};
}

bool SampleTiles::present(int32_t level, int32_t tx, int32_t ty) const {
    if (level < 0 || level >= levelCount()) return false;
    const TileLevel& l = levels_[size_t(level)];
    if (tx < 0 || ty < 0 || tx >= l.tilesAcross || ty >= l.tilesDown) return false;
    return l.tiles.get(tx, ty).present != 0;
}

bool SampleTiles::coarsestComplete() const {
    const TileLevel& l = levels_.back();
    for (int32_t ty = 0; ty < l.tilesDown; ++ty)
        for (int32_t tx = 0; tx < l.tilesAcross; ++tx)
            if (!l.tiles.get(tx, ty).present) return false;
    return true;
}

void* SampleTiles::tileBuffer(int32_t level, int32_t tx, int32_t ty) {
    if (level < 0 || level >= levelCount()) return nullptr;
    TileLevel& l = levels_[size_t(level)];
    if (tx < 0 || ty < 0 || tx >= l.tilesAcross || ty >= l.tilesDown) return nullptr;
    int32_t slot = l.tiles.get(tx, ty).slot;
    if (slot < 0) {
        if (!freeSlots_.empty()) {
            slot = freeSlots_.back();
            freeSlots_.pop_back();
        } else {
            std::unique_ptr<uint8_t[]> bytes(new (std::nothrow) uint8_t[slotBytes_]);
            if (!bytes) return nullptr;
            slots_.push_back(std::move(bytes));
            slotOwner_.emplace_back();
            slotMissing_.emplace_back();
            slot = int32_t(slots_.size()) - 1;
        }
        l.tiles.at(tx, ty).slot = slot;
        slotOwner_[size_t(slot)] = {level, tx, ty};
        slotMissing_[size_t(slot)].clear(); // a reused slot's bits were another tile's
        ++heldSlots_;
    }
    return slots_[size_t(slot)].get();
}

bool SampleTiles::missingRaw(double raw) const {
    return !std::isfinite(raw) || (scale_.hasNodata && raw == scale_.nodataRaw);
}

void SampleTiles::markMissing(int32_t level, int32_t tx, int32_t ty) {
    const TileLevel& l = levels_[size_t(level)];
    const int32_t slot = l.tiles.get(tx, ty).slot;
    const size_t count = size_t(l.tileWidth) * size_t(l.tileHeight);
    // The bits stay until the slot holds another tile: once filled, its samples look valid.
    std::vector<uint8_t>& bits = slotMissing_[size_t(slot)];
    withSamples(type_, slots_[size_t(slot)].get(), [&](auto* samples) {
        for (size_t k = 0; k < count; ++k) {
            if (!missingRaw(double(samples[k])) || (!bits.empty() && marked(bits, k))) continue;
            ++missing_;
            if (bits.empty()) bits.assign((count + 7) / 8, 0);
            bits[k >> 3] |= uint8_t(1u << (k & 7));
        }
    });
}

template <typename ValueAt>
bool SampleTiles::writeFill(int32_t level, int32_t tx, int32_t ty, ValueAt&& rawAt) {
    const TileLevel& l = levels_[size_t(level)];
    const int32_t slot = l.tiles.get(tx, ty).slot;
    const std::vector<uint8_t>& bits = slotMissing_[size_t(slot)];
    if (bits.empty()) return false;
    const size_t count = size_t(l.tileWidth) * size_t(l.tileHeight);
    withSamples(type_, slots_[size_t(slot)].get(), [&](auto* samples) {
        using T = std::remove_pointer_t<decltype(samples)>;
        for (size_t k = 0; k < count; ++k) {
            if (!marked(bits, k)) continue;
            const int32_t u = tx * l.tileWidth + int32_t(k % size_t(l.tileWidth)), v = ty * l.tileHeight + int32_t(k / size_t(l.tileWidth));
            double raw = u < l.width && v < l.height ? rawAt(u, v) : fillRaw_; // past the level's edge: never read
            if constexpr (std::is_integral_v<T>) {
                raw = std::clamp(std::round(raw), double(std::numeric_limits<T>::lowest()), double(std::numeric_limits<T>::max()));
                if (missingRaw(raw)) raw += raw < double(std::numeric_limits<T>::max()) ? 1.0 : -1.0; // never the no-data value
            }
            samples[k] = T(raw);
        }
    });
    return true;
}

void SampleTiles::fillTile(int32_t level, int32_t tx, int32_t ty, SampleRect& changed) {
    if (level == coarsest()) {
        fillCoarsest(changed); // interpolated across the level's gaps: the level is whole
        return;
    }
    const TileLevel& l = levels_[size_t(level)];
    const bool wrote = writeFill(level, tx, ty, [&](int32_t u, int32_t v) {
        if (voidsAsPits_) return fillRaw_;
        // The full-resolution sample at this one's centre, and the coarser surface there.
        const int32_t j = std::clamp(int32_t(std::floor((u + 0.5) * l.scaleX)), 0, width_ - 1);
        const int32_t i = std::clamp(int32_t(std::floor((v + 0.5) * l.scaleY)), 0, height_ - 1);
        return (double(coarserSurface(level, j, i)) - scale_.heightOffset) / scale_.heightScale;
    });
    if (wrote) changed.add(tileRect(level, tx, ty));
}

float SampleTiles::coarserSurface(int32_t level, int32_t j, int32_t i) const {
    for (int32_t c = level + 1; c < coarsest(); ++c) {
        const TileLevel& l = levels_[size_t(c)];
        const BlendCorners b = blendCorners(l, j, i);
        const auto held = [&](int32_t u, int32_t v) { return l.tiles.get(u / l.tileWidth, v / l.tileHeight).present != 0; };
        if (held(b.u0, b.v0) && held(b.u1, b.v0) && held(b.u0, b.v1) && held(b.u1, b.v1)) return blended(c, j, i);
    }
    return blended(coarsest(), j, i);
}

void SampleTiles::fillCoarsest(SampleRect& changed) {
    const int32_t c = coarsest();
    const TileLevel& l = levels_[size_t(c)];
    const size_t w = size_t(l.width), h = size_t(l.height);
    std::vector<float> alongRows, alongColumns;
    if (!voidsAsPits_ && w * h <= kMaxInterpolatedSamples) {
        // The level whole, NaN where a sample is missing; then each missing sample the mean of
        // the linear interpolations across its gap along its row and its column (the nearest
        // valid value where a gap reaches the edge), as the page's loader fills a field held
        // whole (web/loaders/nodata.js); the lowest height where neither line has any.
        std::vector<float> raw(w * h); // float keeps every int16 and float32 sample exactly
        for (size_t v = 0; v < h; ++v)
            for (size_t u = 0; u < w; ++u) raw[v * w + u] = missingAtLevel(l, int32_t(u), int32_t(v)) ? NAN : float(rawAtLevel(l, int32_t(u), int32_t(v)));
        alongRows.assign(w * h, NAN), alongColumns.assign(w * h, NAN);
        for (size_t v = 0; v < h; ++v) interpolateGaps(raw.data() + v * w, 1, w, alongRows.data() + v * w);
        for (size_t u = 0; u < w; ++u) interpolateGaps(raw.data() + u, w, h, alongColumns.data() + u);
    }
    for (int32_t ty = 0; ty < l.tilesDown; ++ty)
        for (int32_t tx = 0; tx < l.tilesAcross; ++tx) {
            const bool wrote = writeFill(c, tx, ty, [&](int32_t u, int32_t v) {
                if (alongRows.empty()) return fillRaw_; // as pits, or a level too large (a COG without overviews)
                const size_t k = size_t(v) * w + size_t(u);
                const double a = alongRows[k], b = alongColumns[k];
                return std::isnan(a) ? (std::isnan(b) ? fillRaw_ : b) : std::isnan(b) ? a : 0.5 * (a + b);
            });
            if (wrote) changed.add(tileRect(c, tx, ty));
        }
}

void SampleTiles::fillAll(SampleRect& changed) {
    // Coarse to fine: each level is filled from the coarser surface, already filled.
    fillCoarsest(changed);
    for (int32_t level = coarsest() - 1; level >= 0; --level)
        for (int32_t s = 0; s < slotCount(); ++s) {
            const TileId& t = slotOwner_[size_t(s)];
            if (t.level == level && present(t.level, t.tx, t.ty)) fillTile(t.level, t.tx, t.ty, changed);
        }
}

void SampleTiles::setVoidsAsPits(bool pits, SampleRect& changed) {
    if (pits == voidsAsPits_) return;
    voidsAsPits_ = pits;
    if (!hasFill_ || missing_ == 0) return;
    fillAll(changed);
    // A pit's walls are detail a smooth fill had not: measured again, so the refinement asks
    // for the finer tiles that follow a void's edge (and lets them go when smooth again).
    for (int32_t s = 0; s < slotCount(); ++s) {
        const TileId t = slotOwner_[size_t(s)];
        if (t.level < 0 || !present(t.level, t.tx, t.ty) || slotMissing_[size_t(s)].empty()) continue;
        levels_[size_t(t.level)].tiles.at(t.tx, t.ty).detail = measureDetail(t.level, t.tx, t.ty);
        updateRegions(tileRect(t.level, t.tx, t.ty), t.level, true, changed);
    }
}

void SampleTiles::interpolateGaps(const float* line, size_t stride, size_t n, float* out) {
    size_t k = 0;
    while (k < n) {
        if (!std::isnan(line[k * stride])) { ++k; continue; }
        const size_t first = k; // a gap: [first, end)
        while (k < n && std::isnan(line[k * stride])) ++k;
        const bool left = first > 0, right = k < n;
        if (!left && !right) return; // the whole line is missing
        const double a = left ? line[(first - 1) * stride] : line[k * stride], b = right ? line[k * stride] : a;
        for (size_t g = first; g < k; ++g) {
            const double t = left && right ? double(g - first + 1) / double(k - first + 1) : 0.0;
            out[g * stride] = float(a + (b - a) * t);
        }
    }
}

float SampleTiles::measureDetail(int32_t level, int32_t tx, int32_t ty) const {
    if (level == 0) return 0.0f; // nothing finer to come
    const TileLevel& l = levels_[size_t(level)];
    const int32_t slot = l.tiles.get(tx, ty).slot;
    const int32_t w = std::min(l.tileWidth, l.width - tx * l.tileWidth), h = std::min(l.tileHeight, l.height - ty * l.tileHeight);
    double detail = 0.0;
    withSamples(type_, slots_[size_t(slot)].get(), [&](auto* samples) {
        // In raw units (metres are a linear map of them), scaled once at the end.
        auto at = [&](int32_t u, int32_t v) { return double(samples[size_t(v) * size_t(l.tileWidth) + size_t(u)]); };
        for (int32_t v = 0; v < h; ++v)
            for (int32_t u = 0; u < w; ++u) {
                const double c = at(u, v);
                if (u > 0 && u + 1 < w) detail = std::max(detail, std::abs(at(u - 1, v) - 2.0 * c + at(u + 1, v)));
                if (v > 0 && v + 1 < h) detail = std::max(detail, std::abs(at(u, v - 1) - 2.0 * c + at(u, v + 1)));
            }
    });
    return float(0.5 * detail * std::abs(scale_.heightScale));
}

bool SampleTiles::completeAt(int32_t level, const SampleRect& r, float& detail) const {
    int32_t tx0, ty0, tx1, ty1;
    tilesCovering(level, r, tx0, ty0, tx1, ty1);
    const TileLevel& l = levels_[size_t(level)];
    detail = 0.0f;
    for (int32_t ty = ty0; ty <= ty1; ++ty)
        for (int32_t tx = tx0; tx <= tx1; ++tx) {
            const TileState& t = l.tiles.get(tx, ty);
            if (!t.present) return false;
            detail = std::max(detail, t.detail);
        }
    return true;
}

void SampleTiles::updateRegions(const SampleRect& around, int32_t level, bool arrived, SampleRect& changed) {
    const int32_t rx0 = std::max(0, around.j0 / regionWidth_), rx1 = std::min(regionsAcross_ - 1, around.j1 / regionWidth_);
    const int32_t ry0 = std::max(0, around.i0 / regionHeight_), ry1 = std::min(regionsDown_ - 1, around.i1 / regionHeight_);
    for (int32_t ry = ry0; ry <= ry1; ++ry)
        for (int32_t rx = rx0; rx <= rx1; ++rx) {
            // The finest complete level: the levels finer than `level` did not change, nor did
            // those between it and the region's level.
            const size_t region = regionOf(rx, ry);
            const int32_t now = regionLevel_[region];
            if (now < level || (!arrived && now > level)) continue;
            const SampleRect r = regionRect(rx, ry);
            float detail = 0.0f;
            int32_t found = level;
            if (arrived) {
                if (!completeAt(level, r, detail)) continue;
            } else {
                found = coarsest();
                for (int32_t l = level + 1; l < coarsest() && found == coarsest(); ++l)
                    if (completeAt(l, r, detail)) found = l;
                if (found == coarsest()) completeAt(found, r, detail);
            }
            regionDetail_[region] = found == 0 ? 0.0f : detail;
            if (found == now) continue;
            regionLevel_[region] = uint8_t(found);
            changed.add(r);
        }
}

bool SampleTiles::commit(int32_t level, int32_t tx, int32_t ty, SampleRect& changed) {
    if (level < 0 || level >= levelCount()) return false;
    TileLevel& l = levels_[size_t(level)];
    if (tx < 0 || ty < 0 || tx >= l.tilesAcross || ty >= l.tilesDown) return false;
    const int32_t slot = l.tiles.get(tx, ty).slot;
    if (slot < 0) return false;
    widenRange(level, tx, ty);
    markMissing(level, tx, ty);
    if (hasFill_) fillTile(level, tx, ty, changed);
    TileState& state = l.tiles.at(tx, ty);
    state.present = 1;
    state.detail = measureDetail(level, tx, ty);
    updateRegions(tileRect(level, tx, ty), level, true, changed);
    return true;
}

bool SampleTiles::evict(int32_t level, int32_t tx, int32_t ty, SampleRect& changed) {
    if (level < 0 || level >= coarsest()) return false; // the coarsest level stays
    TileLevel& l = levels_[size_t(level)];
    if (tx < 0 || ty < 0 || tx >= l.tilesAcross || ty >= l.tilesDown) return false;
    TileState& state = l.tiles.at(tx, ty);
    if (state.slot < 0) return false;
    freeSlots_.push_back(state.slot);
    slotOwner_[size_t(state.slot)] = {};
    state = TileState{};
    --heldSlots_;
    updateRegions(tileRect(level, tx, ty), level, false, changed);
    return true;
}

void SampleTiles::widenRange(int32_t level, int32_t tx, int32_t ty) {
    const TileLevel& l = levels_[size_t(level)];
    const int32_t slot = l.tiles.get(tx, ty).slot;
    const int32_t w = std::min(l.tileWidth, l.width - tx * l.tileWidth), h = std::min(l.tileHeight, l.height - ty * l.tileHeight);
    withSamples(type_, slots_[size_t(slot)].get(), [&](auto* samples) {
        for (int32_t v = 0; v < h; ++v) {
            const auto* row = samples + size_t(v) * size_t(l.tileWidth);
            for (int32_t u = 0; u < w; ++u) {
                const double raw = double(row[u]);
                if (missingRaw(raw)) continue;
                if (!hasRange_) rangeLow_ = rangeHigh_ = raw, hasRange_ = true;
                rangeLow_ = std::min(rangeLow_, raw), rangeHigh_ = std::max(rangeHigh_, raw);
            }
        }
    });
}

bool SampleTiles::rawRange(double& low, double& high) const {
    low = rangeLow_, high = rangeHigh_;
    return hasRange_;
}

void SampleTiles::rescan() {
    if (hasFill_) return; // prepared before: every tile since came with the scale known
    hasRange_ = false;
    for (int32_t s = 0; s < slotCount(); ++s) {
        const TileId t = slotOwner_[size_t(s)];
        if (t.level < 0 || !present(t.level, t.tx, t.ty)) continue;
        widenRange(t.level, t.tx, t.ty);
        markMissing(t.level, t.tx, t.ty);
    }
}

void SampleTiles::setFillRaw(double raw) {
    fillRaw_ = raw;
    const bool first = !hasFill_;
    hasFill_ = true;
    SampleRect changed; // the caller prepares the field before any mesh stands on it
    if (first) fillAll(changed); // later tiles are filled as they come
}

void SampleTiles::range(const SampleRect& rect, float& low, float& high) const {
    low = 1e30f, high = -1e30f;
    const SampleRect r{std::max(rect.j0, 0), std::max(rect.i0, 0), std::min(rect.j1, width_ - 1), std::min(rect.i1, height_ - 1)};
    if (r.empty()) return;
    for (int32_t ry = r.i0 / regionHeight_; ry <= r.i1 / regionHeight_; ++ry)
        for (int32_t rx = r.j0 / regionWidth_; rx <= r.j1 / regionWidth_; ++rx) {
            const SampleRect whole = regionRect(rx, ry);
            const SampleRect part{std::max(r.j0, whole.j0), std::max(r.i0, whole.i0), std::min(r.j1, whole.j1), std::min(r.i1, whole.i1)};
            const int32_t level = regionLevel_[regionOf(rx, ry)];
            // A bilinear blend stays within its four samples: the samples it reaches bound it.
            int32_t u0, v0, u1, v1;
            samplesFor(level, part, u0, v0, u1, v1);
            double rawLow = INFINITY, rawHigh = -INFINITY;
            levelRawRange(level, u0, v0, u1, v1, rawLow, rawHigh);
            // toMetres is monotonic: the extremes of the raw samples give the extremes in metres.
            const float a = toMetres(rawLow), b = toMetres(rawHigh);
            low = std::min(low, std::min(a, b)), high = std::max(high, std::max(a, b));
        }
}

void SampleTiles::levelRawRange(int32_t level, int32_t u0, int32_t v0, int32_t u1, int32_t v1, double& low, double& high) const {
    const TileLevel& l = levels_[size_t(level)];
    for (int32_t ty = v0 / l.tileHeight; ty <= v1 / l.tileHeight; ++ty)
        for (int32_t tx = u0 / l.tileWidth; tx <= u1 / l.tileWidth; ++tx) {
            const int32_t x0 = std::max(u0, tx * l.tileWidth) - tx * l.tileWidth, x1 = std::min(u1, (tx + 1) * l.tileWidth - 1) - tx * l.tileWidth;
            const int32_t y0 = std::max(v0, ty * l.tileHeight) - ty * l.tileHeight, y1 = std::min(v1, (ty + 1) * l.tileHeight - 1) - ty * l.tileHeight;
            withSamples(type_, slots_[size_t(l.tiles.get(tx, ty).slot)].get(), [&](const auto* samples) {
                auto lo = samples[size_t(y0) * size_t(l.tileWidth) + size_t(x0)], hi = lo;
                for (int32_t y = y0; y <= y1; ++y) {
                    const auto* row = samples + size_t(y) * size_t(l.tileWidth);
                    for (int32_t x = x0; x <= x1; ++x) lo = std::min(lo, row[x]), hi = std::max(hi, row[x]);
                }
                low = std::min(low, double(lo)), high = std::max(high, double(hi));
            });
        }
}

int32_t SampleTiles::levelIn(const SampleRect& rect, float& detail) const {
    detail = 0.0f;
    const SampleRect r{std::max(rect.j0, 0), std::max(rect.i0, 0), std::min(rect.j1, width_ - 1), std::min(rect.i1, height_ - 1)};
    if (r.empty()) return 0;
    int32_t level = 0;
    for (int32_t ry = r.i0 / regionHeight_; ry <= r.i1 / regionHeight_; ++ry)
        for (int32_t rx = r.j0 / regionWidth_; rx <= r.j1 / regionWidth_; ++rx) {
            const size_t region = regionOf(rx, ry);
            level = std::max(level, int32_t(regionLevel_[region]));
            detail = std::max(detail, regionDetail_[region]);
        }
    return level;
}

int32_t SampleTiles::finestLevelIn(const SampleRect& rect) const {
    const SampleRect r{std::max(rect.j0, 0), std::max(rect.i0, 0), std::min(rect.j1, width_ - 1), std::min(rect.i1, height_ - 1)};
    int32_t level = coarsest();
    if (r.empty()) return level;
    for (int32_t ry = r.i0 / regionHeight_; ry <= r.i1 / regionHeight_; ++ry)
        for (int32_t rx = r.j0 / regionWidth_; rx <= r.j1 / regionWidth_; ++rx) level = std::min(level, int32_t(regionLevel_[regionOf(rx, ry)]));
    return level;
}

size_t SampleTiles::sampleBytes() const { return size_t(heldSlots_) * slotBytes_; }

size_t SampleTiles::memoryBytes() const {
    size_t bytes = slots_.size() * slotBytes_ + regionLevel_.capacity() + regionDetail_.capacity() * sizeof(float) +
                   slotOwner_.capacity() * sizeof(TileId) + freeSlots_.capacity() * sizeof(int32_t) +
                   slotMissing_.capacity() * sizeof(std::vector<uint8_t>);
    for (const std::vector<uint8_t>& bits : slotMissing_) bytes += bits.capacity();
    for (const TileLevel& l : levels_) bytes += l.tiles.memoryBytes();
    return bytes;
}

} // namespace hexlod
