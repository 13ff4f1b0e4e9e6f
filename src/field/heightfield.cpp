// The height field under paper §4.7; see heightfield.h.
#include "field/heightfield.h"

#include <algorithm>
#include <cmath>
#include <new>

namespace hexlod {

size_t sampleBytes(SampleType type) {
    switch (type) {
        case SampleType::U8: return 1;
        case SampleType::U16: return 2;
        case SampleType::I16: return 2;
        case SampleType::F32: return 4;
    }
    return 0;
}

// The checks every field's size and type pass; null or what is wrong.
static const char* badSize(int32_t width, int32_t height, SampleType type, bool tiled) {
    if (sampleBytes(type) == 0) return "unknown sample type (expected 1=u8, 2=u16, 3=i16, 4=f32)";
    if (width < 2 || height < 2) return "a height field needs at least 2x2 samples";
    if (!tiled && (width > kMaxFieldSide || height > kMaxFieldSide))
        return "a height field held whole is limited to 65536 samples a side (a tiled one, such as a Cloud-Optimized GeoTIFF, to 2097152)";
    if (width > kMaxTiledFieldSide || height > kMaxTiledFieldSide) return "a tiled height field side is limited to 2097152 samples";
    return nullptr;
}

std::unique_ptr<Heightfield> Heightfield::create(int32_t width, int32_t height, SampleType type,
                                                 const char** error) {
    const char* ignored = nullptr;
    if (!error) error = &ignored;
    if ((*error = badSize(width, height, type, false))) return nullptr;
    const uint64_t bytes = uint64_t(width) * uint64_t(height) * sampleBytes(type);
    if (bytes > uint64_t(SIZE_MAX)) {
        *error = "the height field does not fit this address space";
        return nullptr;
    }
    std::unique_ptr<Heightfield> field(new (std::nothrow) Heightfield());
    if (field) field->samples_.reset(new (std::nothrow) uint8_t[size_t(bytes)]);
    if (!field || !field->samples_) {
        *error = "out of memory for the height field samples";
        return nullptr;
    }
    field->width_ = width;
    field->height_ = height;
    field->type_ = type;
    return field;
}

std::unique_ptr<Heightfield> Heightfield::createTiled(int32_t width, int32_t height, SampleType type, int32_t levels,
                                                      const int32_t* dims, const char** error) {
    const char* ignored = nullptr;
    if (!error) error = &ignored;
    if ((*error = badSize(width, height, type, true))) return nullptr;
    std::unique_ptr<Heightfield> field(new (std::nothrow) Heightfield());
    if (field) field->tiles_.reset(new (std::nothrow) SampleTiles());
    if (!field || !field->tiles_) {
        *error = "out of memory for the height field";
        return nullptr;
    }
    if (const char* problem = field->tiles_->init(width, height, type, levels, dims)) {
        *error = problem;
        return nullptr;
    }
    field->width_ = width;
    field->height_ = height;
    field->type_ = type;
    return field;
}

const char* Heightfield::setScale(const HeightfieldScale& scale) {
    const bool finite = std::isfinite(scale.spacingX) && std::isfinite(scale.spacingY) &&
                        std::isfinite(scale.heightScale) && std::isfinite(scale.heightOffset);
    if (!finite) return "spacing, height scale and offset must be finite numbers";
    if (scale.spacingX <= 0.0 || scale.spacingY <= 0.0) return "sample spacing must be positive";
    // Vertex positions are floats from which the mesh recovers lattice points (HexMesh::latticeAt):
    // exact only while positions are normal floats, far inside this range.
    if (std::min(scale.spacingX, scale.spacingY) < kMinSpacing || std::max(scale.spacingX, scale.spacingY) > kMaxSpacing)
        return "sample spacing must be between 1e-6 m and 1e8 m";
    if (scale.heightScale == 0.0) return "height scale must not be zero";
    if (std::abs(scale.heightScale) > kMaxAbsHeight) return "height scale must be at most 1e9 metres per raw unit in magnitude";
    if (std::abs(scale.heightOffset) > kMaxAbsHeight) return "height offset must be between -1e9 m and 1e9 m";
    scale_ = scale;
    if (tiles_) tiles_->setScale(scale);
    return nullptr;
}

bool Heightfield::isMissing(size_t k) const {
    const double raw = rawAt(k);
    if (!std::isfinite(raw)) return true;
    return scale_.hasNodata && raw == scale_.nodataRaw;
}

void Heightfield::setRaw(size_t k, double raw) {
    switch (type_) {
        case SampleType::U8: static_cast<uint8_t*>(samples_.get())[k] = uint8_t(raw); break;
        case SampleType::U16: reinterpret_cast<uint16_t*>(samples_.get())[k] = uint16_t(raw); break;
        case SampleType::I16: reinterpret_cast<int16_t*>(samples_.get())[k] = int16_t(raw); break;
        case SampleType::F32: reinterpret_cast<float*>(samples_.get())[k] = float(raw); break;
    }
}

// The height range of raw extremes, or an error when they are not heights.
static const char* heightsOf(const HeightfieldScale& scale, double lowRaw, double highRaw, double& a, double& b) {
    a = lowRaw * scale.heightScale + scale.heightOffset;
    b = highRaw * scale.heightScale + scale.heightOffset;
    // Beyond this, heights (times the vertical scale) overflow what the criteria (§5) and the
    // camera can hold: most often a nodata value the file does not declare.
    if (!(std::max(std::abs(a), std::abs(b)) <= kMaxAbsHeight))
        return "heights must lie between -1e9 m and 1e9 m after the height scale and offset (is a nodata value undeclared?)";
    return nullptr;
}

bool Heightfield::declareHeightRange(double low, double high) {
    if (!(std::isfinite(low) && std::isfinite(high) && low <= high && std::max(std::abs(low), std::abs(high)) <= kMaxAbsHeight)) return false;
    minHeight_ = std::min(minHeight_, float(low));
    maxHeight_ = std::max(maxHeight_, float(high));
    return true;
}

bool Heightfield::widenHeightRange() {
    double lowRaw, highRaw, a, b;
    if (!tiles_ || !tiles_->rawRange(lowRaw, highRaw) || heightsOf(scale_, lowRaw, highRaw, a, b)) return false;
    const float low = std::min(minHeight_, float(std::min(a, b))), high = std::max(maxHeight_, float(std::max(a, b)));
    const bool grew = low < minHeight_ || high > maxHeight_;
    minHeight_ = low, maxHeight_ = high;
    missingCount_ = tiles_->missingCount();
    return grew;
}

const char* Heightfield::prepare() {
    if (tiles_) {
        // What is present now (the coarsest level at least) gives the range and the fill; each
        // tile that comes later is filled as it is committed.
        if (!tiles_->coarsestComplete()) return "the coarsest level's tiles must all be present before the field is prepared";
        tiles_->rescan(); // committed before the scale said which value is no-data
        double lowRaw, highRaw, a, b;
        if (!tiles_->rawRange(lowRaw, highRaw)) return "every sample is nodata";
        if (const char* problem = heightsOf(scale_, lowRaw, highRaw, a, b)) return problem;
        tiles_->setFillRaw(scale_.heightScale > 0.0 ? lowRaw : highRaw);
        missingCount_ = tiles_->missingCount();
        minHeight_ = float(std::min(a, b));
        maxHeight_ = float(std::max(a, b));
        return nullptr;
    }
    const size_t n = sampleCount();
    double lowRaw = 0.0, highRaw = 0.0;
    bool any = false;
    size_t missing = 0;
    for (size_t k = 0; k < n; ++k) {
        if (isMissing(k)) {
            ++missing;
            continue;
        }
        const double raw = rawAt(k);
        if (!any) lowRaw = highRaw = raw, any = true;
        lowRaw = std::min(lowRaw, raw);
        highRaw = std::max(highRaw, raw);
    }
    if (!any) return "every sample is nodata";
    double a, b;
    if (const char* problem = heightsOf(scale_, lowRaw, highRaw, a, b)) return problem;
    // A negative scale flips which raw extreme is the lowest height.
    const double fillRaw = scale_.heightScale > 0.0 ? lowRaw : highRaw;
    missingCount_ = missing;
    if (missingCount_ > 0) {
        for (size_t k = 0; k < n; ++k)
            if (isMissing(k)) setRaw(k, fillRaw);
    }
    minHeight_ = float(std::min(a, b));
    maxHeight_ = float(std::max(a, b));
    return nullptr;
}

float Heightfield::tiledHeightAt(int32_t j, int32_t i) const { return tiles_->height(j, i); }
bool Heightfield::tiledMissing(int32_t j, int32_t i) const { return tiles_->missing(j, i); }

float Heightfield::heightClamped(int32_t j, int32_t i) const {
    j = std::clamp(j, 0, width_ - 1);
    i = std::clamp(i, 0, height_ - 1);
    return heightAt(j, i);
}

float Heightfield::heightAtPosition(double xMetres, double zMetres) const {
    const double u = std::clamp(xMetres / scale_.spacingX, 0.0, double(width_ - 1));
    const double v = std::clamp(zMetres / scale_.spacingY, 0.0, double(height_ - 1));
    const int32_t j = std::min(int32_t(u), width_ - 2);
    const int32_t i = std::min(int32_t(v), height_ - 2);
    const double fu = u - j, fv = v - i;
    const double top = heightAt(j, i) * (1.0 - fu) + heightAt(j + 1, i) * fu;
    const double bottom = heightAt(j, i + 1) * (1.0 - fu) + heightAt(j + 1, i + 1) * fu;
    return float(top * (1.0 - fv) + bottom * fv);
}

} // namespace hexlod
