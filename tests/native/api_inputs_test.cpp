// What the C ABI refuses (api/hexlod.h, the ranges in the comments of hexlod_camera,
// hexlod_settings and hexlod_scale): non-finite, non-positive and absurd numbers, each refusal a
// message naming the field, and a refused call changes nothing (the previous camera, settings,
// scale and mesh stay). The documented limits themselves are accepted.
#include "api/hexlod.h"

#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "fixture.h"

namespace {

using hexlod::test::kVolcano;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string lastError() { return hexlod_last_error(); }

hexlod_frame query(hexlod_terrain* t) {
    hexlod_frame out{};
    EXPECT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_QUERY | HEXLOD_FRAME_HASH, &out), 0);
    return out;
}

uint64_t hashOf(const hexlod_frame& f) { return uint64_t(f.hash_high) << 32 | f.hash_low; }

// The volcano (87 x 61 samples, 10 m) through the ABI, with its mesh.
hexlod_terrain* volcano() {
    const auto data = hexlod::test::readF32(kVolcano);
    if (data.empty()) return nullptr;
    hexlod_terrain* t = hexlod_terrain_create(kVolcano.width, kVolcano.height, HEXLOD_SAMPLE_F32);
    std::memcpy(hexlod_terrain_samples(t), data.data(), data.size() * sizeof(float));
    hexlod_scale scale{};
    scale.spacing_x_m = kVolcano.spacingX;
    scale.spacing_y_m = kVolcano.spacingY;
    EXPECT_EQ(hexlod_terrain_set_scale(t, &scale), 0);
    EXPECT_EQ(hexlod_terrain_prepare(t, nullptr), 0);
    EXPECT_EQ(hexlod_terrain_reset_mesh(t, nullptr), 0);
    return t;
}

// South of the crater, 300 m up, looking at it: 1920 x 1080, 60 degrees.
hexlod_camera goodCamera() {
    return hexlod_camera{{430.0, 300.0, 900.0}, {430.0, 120.0, 300.0}, {0, 0, 0}, 0.57735026918962573, 16.0 / 9.0, 1080.0, 1.0, 1e5};
}

// Frames with the camera until converged; returns the updates taken.
int32_t converge(hexlod_terrain* t, const hexlod_camera* camera) {
    hexlod_frame out{};
    for (int32_t n = 1; n <= 200; ++n) {
        EXPECT_EQ(hexlod_terrain_frame(t, n == 1 ? camera : nullptr, HEXLOD_FRAME_ALL, &out), 0) << lastError();
        if (out.converged) return n;
    }
    ADD_FAILURE() << "no convergence in 200 frames";
    return -1;
}

// The mesh, its stream and the refiner's state as a refused call must leave them: the same hash
// and stream version now, and a further frame that finds nothing to do (the previous camera
// and settings still hold, and the mesh had converged for them).
void expectUnchanged(hexlod_terrain* t, const hexlod_frame& before, const std::string& what) {
    const hexlod_frame now = query(t);
    EXPECT_EQ(hashOf(now), hashOf(before)) << what;
    EXPECT_EQ(now.version, before.version) << what;
    EXPECT_EQ(now.triangles, before.triangles) << what;
    hexlod_frame out{};
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
    EXPECT_EQ(out.operations, 0) << what << ": the previous camera and settings were kept";
    EXPECT_EQ(out.converged, 1) << what;
    EXPECT_EQ(hashOf(query(t)), hashOf(before)) << what;
}

struct CameraCase {
    const char* field; // the name the message must give
    std::function<void(hexlod_camera&)> spoil;
};

} // namespace

TEST(ApiInputs, CameraFieldsOutsideTheirRangesAreRefusedNamingTheFieldAndTheMeshStays) {
    hexlod_terrain* t = volcano();
    ASSERT_NE(t, nullptr);
    const hexlod_camera good = goodCamera();
    converge(t, &good);
    const hexlod_frame before = query(t);
    ASSERT_GT(before.triangles, 0.0);

    const std::vector<CameraCase> cases = {
        {"viewport_height_px", [](hexlod_camera& c) { c.viewport_height_px = kInf; }}, // it refined to full resolution
        {"viewport_height_px", [](hexlod_camera& c) { c.viewport_height_px = kNaN; }},
        {"viewport_height_px", [](hexlod_camera& c) { c.viewport_height_px = 0.0; }},
        {"viewport_height_px", [](hexlod_camera& c) { c.viewport_height_px = -1080.0; }},
        {"viewport_height_px", [](hexlod_camera& c) { c.viewport_height_px = 0.5; }},
        {"viewport_height_px", [](hexlod_camera& c) { c.viewport_height_px = 100001.0; }},
        {"eye[0]", [](hexlod_camera& c) { c.eye[0] = kNaN; }},
        {"eye[1]", [](hexlod_camera& c) { c.eye[1] = kInf; }},
        {"eye[2]", [](hexlod_camera& c) { c.eye[2] = -kInf; }},
        {"eye[1]", [](hexlod_camera& c) { c.eye[1] = 1.0001e12; }},
        {"target[0]", [](hexlod_camera& c) { c.target[0] = kNaN; }},
        {"target[2]", [](hexlod_camera& c) { c.target[2] = -2e12; }},
        {"up[1]", [](hexlod_camera& c) { c.up[1] = kInf; }},
        {"up is (", [](hexlod_camera& c) { c.up[1] = 1e-7; }},
        {"tan_half_fov_y", [](hexlod_camera& c) { c.tan_half_fov_y = 0.0; }},
        {"tan_half_fov_y", [](hexlod_camera& c) { c.tan_half_fov_y = -0.5; }},
        {"tan_half_fov_y", [](hexlod_camera& c) { c.tan_half_fov_y = kNaN; }},
        {"tan_half_fov_y", [](hexlod_camera& c) { c.tan_half_fov_y = kInf; }},
        {"tan_half_fov_y", [](hexlod_camera& c) { c.tan_half_fov_y = 0.99e-4; }},
        {"tan_half_fov_y", [](hexlod_camera& c) { c.tan_half_fov_y = 1.01e4; }},
        {"aspect", [](hexlod_camera& c) { c.aspect = 0.0; }},
        {"aspect", [](hexlod_camera& c) { c.aspect = -1.0; }},
        {"aspect", [](hexlod_camera& c) { c.aspect = kInf; }},
        {"aspect", [](hexlod_camera& c) { c.aspect = kNaN; }},
        {"aspect", [](hexlod_camera& c) { c.aspect = 2e4; }},
        {"near_m", [](hexlod_camera& c) { c.near_m = 0.0; }},
        {"near_m", [](hexlod_camera& c) { c.near_m = -1.0; }},
        {"near_m", [](hexlod_camera& c) { c.near_m = kNaN; }},
        {"near_m", [](hexlod_camera& c) { c.near_m = 1e-7; }},
        {"near_m", [](hexlod_camera& c) { c.near_m = c.far_m; }},
        {"near_m", [](hexlod_camera& c) { c.near_m = 2.0 * c.far_m; }},
        {"far_m", [](hexlod_camera& c) { c.far_m = kInf; }},
        {"far_m", [](hexlod_camera& c) { c.far_m = kNaN; }},
        {"far_m", [](hexlod_camera& c) { c.far_m = 0.0; }},
        {"far_m", [](hexlod_camera& c) { c.far_m = 1.01e12; }},
        {"eye on the target", [](hexlod_camera& c) { std::memcpy(c.target, c.eye, sizeof(c.eye)); }},
        {"eye on the target", [](hexlod_camera& c) { c.target[0] = c.eye[0] + 5e-7; c.target[1] = c.eye[1]; c.target[2] = c.eye[2]; }},
        {"along the view", [](hexlod_camera& c) { c.target[0] = c.eye[0]; c.target[1] = 0.0; c.target[2] = c.eye[2]; }}, // straight down, up +y
        {"along the view", [](hexlod_camera& c) { c.target[0] = c.eye[0]; c.target[1] = 900.0; c.target[2] = c.eye[2]; c.up[1] = -3.0; }},
    };
    for (const CameraCase& k : cases) {
        hexlod_camera bad = good;
        k.spoil(bad);
        hexlod_frame out{};
        ASSERT_EQ(hexlod_terrain_frame(t, &bad, HEXLOD_FRAME_ALL, &out), HEXLOD_ERROR) << k.field;
        const std::string message = lastError();
        EXPECT_EQ(message.rfind("degenerate camera: ", 0), 0u) << message;
        EXPECT_NE(message.find(k.field), std::string::npos) << "the message names " << k.field << ": " << message;
        expectUnchanged(t, before, message);
    }
    // A camera-only step refuses the same way.
    hexlod_camera bad = good;
    bad.viewport_height_px = kInf;
    hexlod_frame out{};
    EXPECT_EQ(hexlod_terrain_frame(t, &bad, HEXLOD_FRAME_CAMERA, &out), HEXLOD_ERROR);
    expectUnchanged(t, before, "camera step");
    hexlod_terrain_destroy(t);
}

TEST(ApiInputs, CamerasAtTheDocumentedLimitsAreAccepted) {
    hexlod_terrain* t = volcano();
    ASSERT_NE(t, nullptr);
    const std::vector<std::function<void(hexlod_camera&)>> limits = {
        [](hexlod_camera& c) { c.viewport_height_px = 1.0; },
        [](hexlod_camera& c) { c.viewport_height_px = 1e5; },
        [](hexlod_camera& c) { c.tan_half_fov_y = 1e-4; },
        [](hexlod_camera& c) { c.tan_half_fov_y = 1e4; },
        [](hexlod_camera& c) { c.aspect = 1e-4; },
        [](hexlod_camera& c) { c.aspect = 1e4; },
        [](hexlod_camera& c) { c.near_m = 1e-6; },
        [](hexlod_camera& c) { c.far_m = 1e12; },
        [](hexlod_camera& c) { c.eye[0] = -1e12; c.eye[1] = 1e12; c.far_m = 1e12; },
        [](hexlod_camera& c) { c.target[0] = c.eye[0]; c.target[1] = c.eye[1] - 2e-6; c.target[2] = c.eye[2]; c.up[2] = -1.0; },
        [](hexlod_camera& c) { c.target[0] = c.eye[0]; c.target[1] = c.eye[1] + 1e3; c.target[2] = c.eye[2]; c.up[2] = -1e-6; },
        [](hexlod_camera& c) { c.up[0] = 1e12; c.up[1] = 1e12; }, // any length: up is normalised
        [](hexlod_camera& c) { c.up[1] = 1e-6; },
    };
    for (size_t k = 0; k < limits.size(); ++k) {
        hexlod_camera camera = goodCamera();
        limits[k](camera);
        hexlod_frame out{};
        EXPECT_EQ(hexlod_terrain_frame(t, &camera, HEXLOD_FRAME_ALL, &out), 0) << "limit " << k << ": " << lastError();
    }
    hexlod_terrain_destroy(t);
}

TEST(ApiInputs, SettingsOutsideTheirRangesAreRefusedNamingTheFieldAndTheSettingsStay) {
    hexlod_terrain* t = volcano();
    ASSERT_NE(t, nullptr);
    const hexlod_camera camera = goodCamera();
    hexlod_settings good{};
    good.tau_px = 2.0;
    ASSERT_EQ(hexlod_terrain_set_settings(t, &good), 0);
    converge(t, &camera);
    const hexlod_frame before = query(t);

    struct SettingsCase {
        const char* field;
        std::function<void(hexlod_settings&)> spoil;
    };
    const std::vector<SettingsCase> cases = {
        {"tau_px", [](hexlod_settings& s) { s.tau_px = -1.0; }},
        {"tau_px", [](hexlod_settings& s) { s.tau_px = kNaN; }},
        {"tau_px", [](hexlod_settings& s) { s.tau_px = kInf; }},
        {"tau_px", [](hexlod_settings& s) { s.tau_px = 0.009; }}, // would refine the volcano to its samples
        {"tau_px", [](hexlod_settings& s) { s.tau_px = 10001.0; }},
        {"max_error_m", [](hexlod_settings& s) { s.max_error_m = -1.0; }},
        {"max_error_m", [](hexlod_settings& s) { s.max_error_m = kNaN; }},
        {"max_error_m", [](hexlod_settings& s) { s.max_error_m = kInf; }},
        {"max_error_m", [](hexlod_settings& s) { s.max_error_m = 1e-9; }},
        {"max_error_m", [](hexlod_settings& s) { s.max_error_m = 2e9; }},
        {"vertical_scale", [](hexlod_settings& s) { s.vertical_scale = -2.0; }},
        {"vertical_scale", [](hexlod_settings& s) { s.vertical_scale = kNaN; }},
        {"vertical_scale", [](hexlod_settings& s) { s.vertical_scale = kInf; }},
        {"vertical_scale", [](hexlod_settings& s) { s.vertical_scale = 0.0009; }},
        {"vertical_scale", [](hexlod_settings& s) { s.vertical_scale = 1001.0; }},
        {"budget_ms", [](hexlod_settings& s) { s.budget_ms = -1.0; }},
        {"budget_ms", [](hexlod_settings& s) { s.budget_ms = kNaN; }},
        {"budget_ms", [](hexlod_settings& s) { s.budget_ms = kInf; }},
        {"budget_ms", [](hexlod_settings& s) { s.budget_ms = 60001.0; }},
        {"max_operations", [](hexlod_settings& s) { s.max_operations = -1; }},
        {"max_operations", [](hexlod_settings& s) { s.max_operations = INT_MIN; }},
        {"max_triangles", [](hexlod_settings& s) { s.max_triangles = -1; }},
        {"morph_frames", [](hexlod_settings& s) { s.morph_frames = -1; }},
        {"morph_frames", [](hexlod_settings& s) { s.morph_frames = 1001; }},
        {"layout", [](hexlod_settings& s) { s.layout = 2; }},
        {"layout", [](hexlod_settings& s) { s.layout = -1; }},
    };
    for (const SettingsCase& k : cases) {
        hexlod_settings bad = good;
        k.spoil(bad);
        ASSERT_EQ(hexlod_terrain_set_settings(t, &bad), HEXLOD_ERROR) << k.field;
        const std::string message = lastError();
        EXPECT_EQ(message.rfind(std::string("settings: ") + k.field + " is ", 0), 0u) << message;
        expectUnchanged(t, before, message);
    }
    hexlod_terrain_destroy(t);
}

TEST(ApiInputs, SettingsAtTheDocumentedLimitsAreAccepted) {
    hexlod_terrain* t = volcano();
    ASSERT_NE(t, nullptr);
    const std::vector<std::function<void(hexlod_settings&)>> limits = {
        [](hexlod_settings& s) { s.tau_px = 0.01; },         [](hexlod_settings& s) { s.tau_px = 1e4; },
        [](hexlod_settings& s) { s.max_error_m = 1e-6; },    [](hexlod_settings& s) { s.max_error_m = 1e9; },
        [](hexlod_settings& s) { s.vertical_scale = 1e-3; }, [](hexlod_settings& s) { s.vertical_scale = 1e3; },
        [](hexlod_settings& s) { s.budget_ms = 6e4; },       [](hexlod_settings& s) { s.max_operations = INT_MAX; },
        [](hexlod_settings& s) { s.max_triangles = INT_MAX; }, [](hexlod_settings& s) { s.morph_frames = 1000; },
        [](hexlod_settings& s) { s.auto_tau = -7; s.no_frustum_culling = 2; s.no_normals = INT_MIN; }, // flags: non-zero is set
    };
    for (size_t k = 0; k < limits.size(); ++k) {
        hexlod_settings settings{};
        limits[k](settings);
        EXPECT_EQ(hexlod_terrain_set_settings(t, &settings), 0) << "limit " << k << ": " << lastError();
    }
    hexlod_terrain_destroy(t);
}

TEST(ApiInputs, AbsurdScalesAndHeightsAreRefusedAndTheTerrainStays) {
    hexlod_terrain* t = volcano();
    ASSERT_NE(t, nullptr);
    const hexlod_camera camera = goodCamera();
    converge(t, &camera);
    const hexlod_frame before = query(t);
    double heightBefore = 0.0;
    ASSERT_EQ(hexlod_terrain_height_at(t, 430.0, 300.0, HEXLOD_SURFACE_FIELD, &heightBefore), 1);

    hexlod_scale good{};
    good.spacing_x_m = kVolcano.spacingX;
    good.spacing_y_m = kVolcano.spacingY;
    const std::vector<std::pair<const char*, std::function<void(hexlod_scale&)>>> cases = {
        {"finite", [](hexlod_scale& s) { s.spacing_x_m = kNaN; }},
        {"finite", [](hexlod_scale& s) { s.height_scale = kInf; }},
        {"finite", [](hexlod_scale& s) { s.height_offset_m = -kInf; }},
        {"spacing must be positive", [](hexlod_scale& s) { s.spacing_y_m = -10.0; }},
        {"spacing must be between", [](hexlod_scale& s) { s.spacing_x_m = 1e9; }},
        {"height scale", [](hexlod_scale& s) { s.height_scale = 2e9; }},
        {"height offset", [](hexlod_scale& s) { s.height_offset_m = -2e9; }},
        // Within the scale's own limits, but the volcano's 195 m peak would stand at 1.95e9 m.
        {"heights must lie between", [](hexlod_scale& s) { s.height_scale = 1e7; }},
    };
    for (const auto& [words, spoil] : cases) {
        hexlod_scale bad = good;
        spoil(bad);
        EXPECT_EQ(hexlod_terrain_set_scale(t, &bad), HEXLOD_ERROR) << words;
        EXPECT_NE(lastError().find(words), std::string::npos) << lastError();
        double height = 0.0;
        ASSERT_EQ(hexlod_terrain_height_at(t, 430.0, 300.0, HEXLOD_SURFACE_FIELD, &height), 1);
        EXPECT_EQ(height, heightBefore) << words << ": the previous scale stays";
        expectUnchanged(t, before, lastError());
    }
    hexlod_terrain_destroy(t);

    // prepare: a valid sample whose height is absurd (an undeclared nodata value) is refused
    // and the field stays as the last successful prepare left it.
    hexlod_terrain* small = hexlod_terrain_create(3, 3, HEXLOD_SAMPLE_F32);
    float* samples = static_cast<float*>(hexlod_terrain_samples(small));
    for (int k = 0; k < 9; ++k) samples[k] = float(k);
    samples[4] = std::numeric_limits<float>::quiet_NaN();
    hexlod_field_info info{};
    ASSERT_EQ(hexlod_terrain_prepare(small, &info), 0);
    EXPECT_EQ(info.max_height_m, 8.0);
    samples[7] = -3.4e38f;
    EXPECT_EQ(hexlod_terrain_prepare(small, &info), HEXLOD_ERROR);
    EXPECT_NE(lastError().find("heights must lie between -1e9 m and 1e9 m"), std::string::npos) << lastError();
    EXPECT_EQ(info.max_height_m, 8.0) << "info is not written on failure";
    samples[7] = 1e9f; // the limit itself
    samples[4] = 5.0f;
    EXPECT_EQ(hexlod_terrain_prepare(small, &info), 0) << lastError();
    hexlod_terrain_destroy(small);
}

TEST(ApiInputs, NonFinitePositionsHaveNoHeightAndUnknownFrameStepsAreRefused) {
    hexlod_terrain* t = volcano();
    ASSERT_NE(t, nullptr);
    hexlod_frame out{};
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
    for (const int32_t surface : {HEXLOD_SURFACE_FIELD, HEXLOD_SURFACE_DRAWN}) {
        for (const auto& [x, z] : std::vector<std::pair<double, double>>{{kNaN, 100.0}, {100.0, kInf}, {-kInf, kNaN}}) {
            double h = 0.0;
            EXPECT_EQ(hexlod_terrain_height_at(t, x, z, surface, &h), 0) << surface;
            EXPECT_TRUE(std::isnan(h));
        }
        double h = kNaN;
        EXPECT_EQ(hexlod_terrain_height_at(t, 430.0, 300.0, surface, &h), 1);
        EXPECT_TRUE(std::isfinite(h));
    }
    double h = 0.0;
    EXPECT_EQ(hexlod_terrain_height_at(t, kNaN, 0.0, 7, &h), HEXLOD_ERROR) << "an unknown surface is refused first";
    EXPECT_EQ(hexlod_terrain_frame(t, nullptr, 64, &out), HEXLOD_ERROR);
    EXPECT_NE(lastError().find("unknown frame steps"), std::string::npos);
    EXPECT_EQ(hexlod_terrain_frame(t, nullptr, -1, &out), HEXLOD_ERROR);
    EXPECT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_QUERY | HEXLOD_FRAME_HASH | HEXLOD_FRAME_CENSUS, &out), 0);
    hexlod_terrain_destroy(t);
}

TEST(ApiInputs, EarthShapesOutsideTheirRangesAreRefusedAndTheShapeStays) {
    hexlod_terrain* t = volcano();
    ASSERT_NE(t, nullptr);
    const hexlod_camera good = goodCamera();
    converge(t, &good);
    const hexlod_frame before = query(t);
    const struct {
        const char* names;
        int32_t kind;
        double ox, oz, radius, lat0, kx, kz;
    } cases[] = {
        {"kind", 3, 0, 0, 6.4e6, 0, 1e6, 1e6},
        {"origin", HEXLOD_EARTH_SPHERE, kNaN, 0, 6.4e6, 0, 1e6, 1e6},
        {"radius_m", HEXLOD_EARTH_SPHERE, 0, 0, 10.0, 0, 1e6, 1e6},
        {"radius_m", HEXLOD_EARTH_SPHERE, 0, 0, kInf, 0, 1e6, 1e6},
        {"latitude0_rad", HEXLOD_EARTH_GEOGRAPHIC, 0, 0, 6.4e6, 2.0, 1e6, 1e6},
        {"metres per radian", HEXLOD_EARTH_GEOGRAPHIC, 0, 0, 6.4e6, 0.5, 0.0, 1e6},
        {"metres per radian", HEXLOD_EARTH_GEOGRAPHIC, 0, 0, 6.4e6, 0.5, 1e6, kNaN},
    };
    for (const auto& c : cases) {
        EXPECT_EQ(hexlod_terrain_set_earth(t, c.kind, c.ox, c.oz, c.radius, c.lat0, c.kx, c.kz), HEXLOD_ERROR) << c.names;
        EXPECT_NE(lastError().find(c.names), std::string::npos) << lastError();
        expectUnchanged(t, before, c.names);
    }
    // A good shape is taken, survives new settings, and makes the mesh refine for the curvature.
    ASSERT_EQ(hexlod_terrain_set_earth(t, HEXLOD_EARTH_SPHERE, 435.0, 300.0, 1e4, 0.0, 1.0, 1.0), 0) << lastError();
    hexlod_settings settings{};
    settings.tau_px = 1.0;
    ASSERT_EQ(hexlod_terrain_set_settings(t, &settings), 0);
    hexlod_frame out{};
    ASSERT_EQ(hexlod_terrain_frame(t, nullptr, HEXLOD_FRAME_ALL, &out), 0);
    EXPECT_GT(out.operations, 0) << "a sphere of 10 km bends a field of 870 m: the mesh follows";
    hexlod_terrain_destroy(t);
}
