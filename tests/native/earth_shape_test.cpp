// The curved Earth (lod/earth_shape.h): its positions against WGS 84 and sphere formulas written
// here, its cell bounds against brute force, and the refinement's tau bound (paper §5) on the
// curved surface as drawn: straight triangles between curved vertices.
#include "lod/earth_shape.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <glm/geometric.hpp>

#include "fixture.h"
#include "samples_under_triangles.h"
#include "lod/refiner.h"

using namespace hexlod;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// WGS 84 by the textbook: geodetic to Earth-centred, then east, north, up at an origin.
glm::dvec3 ecef(double lat, double lon, double h) {
    const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
    const double n = a / std::sqrt(1.0 - e2 * std::sin(lat) * std::sin(lat));
    return {(n + h) * std::cos(lat) * std::cos(lon), (n + h) * std::cos(lat) * std::sin(lon), (n * (1.0 - e2) + h) * std::sin(lat)};
}

glm::dvec3 eastUpSouth(double lat0, double lon0, const glm::dvec3& p) {
    const glm::dvec3 d = p - ecef(lat0, lon0, 0.0);
    const glm::dvec3 east(-std::sin(lon0), std::cos(lon0), 0.0);
    const glm::dvec3 north(-std::sin(lat0) * std::cos(lon0), -std::sin(lat0) * std::sin(lon0), std::cos(lat0));
    const glm::dvec3 up(std::cos(lat0) * std::cos(lon0), std::cos(lat0) * std::sin(lon0), std::sin(lat0));
    return {glm::dot(d, east), glm::dot(d, up), -glm::dot(d, north)};
}

EarthShape geographic(double lat0Deg, double perRadian) {
    EarthShape e;
    e.kind = EarthKind::Geographic;
    e.originX = 1000.0, e.originZ = 2000.0;
    e.latitude0 = lat0Deg * kDeg;
    e.metresPerRadianX = e.metresPerRadianZ = perRadian;
    return e;
}

EarthShape sphere() {
    EarthShape e;
    e.kind = EarthKind::Sphere;
    e.originX = 500.0, e.originZ = -300.0;
    e.radius = 6371008.8;
    return e;
}

} // namespace

TEST(EarthShape, GeographicPointsLieWhereWgs84PutsThem) {
    const double lon0 = 37.0 * kDeg; // any: the frame's meridian is the origin's
    for (double lat0 : {0.0, 45.0, -70.0, 89.0}) {
        const EarthShape e = geographic(lat0, 6.0e6);
        std::mt19937 random(7);
        std::uniform_real_distribution<double> offset(-3.0e6, 3.0e6), height(-500.0, 9000.0);
        for (int32_t k = 0; k < 2000; ++k) {
            const double x = e.originX + offset(random), z = e.originZ + offset(random), h = height(random);
            const double lat = e.latitude0 - (z - e.originZ) / e.metresPerRadianZ, lon = lon0 + (x - e.originX) / e.metresPerRadianX;
            if (std::abs(lat) > 0.5 * kPi) continue;
            const glm::dvec3 expected = eastUpSouth(e.latitude0, lon0, ecef(lat, lon, h));
            const glm::dvec3 got = curvedPosition(e, x, h, z);
            ASSERT_LT(glm::length(got - expected), 1e-3) << "lat0 " << lat0 << " at " << x << ", " << z;
            // The normal: the direction a height moves the point.
            const glm::dvec3 up = glm::normalize(eastUpSouth(e.latitude0, lon0, ecef(lat, lon, h + 1.0)) - expected);
            ASSERT_LT(glm::length(curvedUp(e, x, z) - up), 1e-6);
        }
    }
}

TEST(EarthShape, TheSphereKeepsDistancesFromItsOriginAndHeightsAboveIt) {
    const EarthShape e = sphere();
    const glm::dvec3 center(0.0, -e.radius, 0.0);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> offset(-4.0e6, 4.0e6), height(-500.0, 9000.0);
    for (int32_t k = 0; k < 2000; ++k) {
        const double dx = offset(random), dz = offset(random), h = height(random);
        const glm::dvec3 p = curvedPosition(e, e.originX + dx, h, e.originZ + dz);
        ASSERT_NEAR(glm::length(p - center), e.radius + h, 1e-6);
        // The great-circle distance from the origin's point is the flat distance.
        const double angle = std::acos(std::clamp(glm::dot(glm::normalize(p - center), glm::dvec3(0, 1, 0)), -1.0, 1.0));
        ASSERT_NEAR(angle * e.radius, std::hypot(dx, dz), 1e-3);
        // In the flat direction from the origin.
        ASSERT_NEAR(std::atan2(p.z, p.x), std::atan2(dz, dx), 1e-9);
    }
    EXPECT_EQ(curvedPosition(e, e.originX, 12.5, e.originZ), glm::dvec3(0.0, 12.5, 0.0));
}

// The three promises of a CurvedCell, by brute force over random cells of 10 m to 800 km.
TEST(EarthShape, ACellsImageLiesInItsSphereAndItsTrianglesWithinTheSag) {
    for (const EarthShape& e : {sphere(), geographic(0.0, 6.4e6), geographic(52.0, 6.4e6), geographic(-75.0, 3.0e6)}) {
        std::mt19937 random(11);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        double worstSagUse = 0.0, worstRadiusUse = 0.0, worstTiltUse = 0.0;
        for (int32_t k = 0; k < 3000; ++k) {
            const double size = std::pow(10.0, 1.0 + 4.9 * unit(random)); // 10 m to 800 km
            const double cx = e.originX + (unit(random) - 0.5) * 4.0e6, cz = e.originZ + (unit(random) - 0.5) * 4.0e6;
            if (e.kind == EarthKind::Geographic && std::abs(e.latitude0 - (cz - e.originZ) / e.metresPerRadianZ) + size / e.metresPerRadianZ > 0.5 * kPi)
                continue; // past a pole
            const double low = -400.0 + 6000.0 * unit(random), high = low + 3000.0 * unit(random);
            const double x0 = cx - 0.5 * size, x1 = cx + 0.5 * size, z0 = cz - 0.4 * size, z1 = cz + 0.4 * size;
            const glm::dvec3 lo(x0, low, z0), hi(x1, high, z1), c = 0.5 * (lo + hi);
            const double r = 0.5 * glm::length(hi - lo), halfDiagonal = 0.5 * std::hypot(x1 - x0, z1 - z0);
            const CurvedCell cell = curvedCell(e, c, r, halfDiagonal, low, high);
            auto inBox = [&] {
                return glm::dvec3(x0 + (x1 - x0) * unit(random), low + (high - low) * unit(random), z0 + (z1 - z0) * unit(random));
            };
            for (int32_t n = 0; n < 20; ++n) {
                // A point of the flat sphere is drawn within the curved radius.
                glm::dvec3 d(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5);
                const glm::dvec3 p = c + r * unit(random) * glm::normalize(d);
                const double away = glm::length(curvedPosition(e, p.x, p.y, p.z) - cell.center);
                worstRadiusUse = std::max(worstRadiusUse, away / cell.radius);
                ASSERT_LE(away, cell.radius * (1.0 + 1e-9) + 1e-6);
                // A triangle of three footprint points: straight between their images, off the
                // image of the flat triangle by at most the sag.
                const glm::dvec3 a = inBox(), b = inBox(), t = inBox();
                double w0 = unit(random), w1 = unit(random);
                if (w0 + w1 > 1.0) w0 = 1.0 - w0, w1 = 1.0 - w1;
                const double w2 = 1.0 - w0 - w1;
                const glm::dvec3 flat = w0 * a + w1 * b + w2 * t;
                const glm::dvec3 drawn = w0 * curvedPosition(e, a.x, a.y, a.z) + w1 * curvedPosition(e, b.x, b.y, b.z) +
                                         w2 * curvedPosition(e, t.x, t.y, t.z);
                // Along the cell's up at most the sag (the normals it stands along are within
                // the tilt of up) and the drift; across it the drift and the sag's lean.
                const glm::dvec3 off = drawn - curvedPosition(e, flat.x, flat.y, flat.z);
                const double along = std::abs(glm::dot(off, cell.up)), across = glm::length(off - glm::dot(off, cell.up) * cell.up);
                worstSagUse = std::max(worstSagUse, (along + across) / std::max(cell.sag + cell.drift, 1e-12));
                ASSERT_LE(along, (cell.sag + cell.drift) * (1.0 + 1e-9) + 1e-6) << "size " << size;
                ASSERT_LE(across, (cell.drift + cell.sag * std::sin(std::min(1.0, cell.tilt))) * (1.0 + 1e-9) + 1e-6) << "size " << size;
                // The normal anywhere under the cell is within the tilt of its up.
                const double turn = std::acos(std::clamp(glm::dot(curvedUp(e, flat.x, flat.z), cell.up), -1.0, 1.0));
                worstTiltUse = std::max(worstTiltUse, turn / std::max(cell.tilt, 1e-12));
                ASSERT_LE(turn, cell.tilt + 1e-7);
            }
        }
        std::printf("earth kind %d: radius used %.3f, sag used %.3f, tilt used %.3f of its bound\n", int(e.kind), worstRadiusUse,
                    worstSagUse, worstTiltUse);
        // Bounds that are not loose by much: the refinement pays for every metre of them.
        EXPECT_GT(worstSagUse, 0.1);
    }
}

namespace {

constexpr double kTanHalf60 = 0.57735026918962573;

// The Grand Canyon's samples 2 km apart: a field of 1,022 km, where the Earth's curvature drops
// its edges by some 20 km from the centre's tangent plane.
std::unique_ptr<Heightfield> continentalField() {
    auto field = test::loadFixture(test::kGrandCanyon);
    if (!field) return nullptr;
    HeightfieldScale scale = field->scale();
    scale.spacingX = scale.spacingY = 2000.0;
    field->setScale(scale);
    return field;
}

// A mesh over the field, refined on `earth` (updates until converged, at most 200).
struct Refinement {
    HexMesh mesh;
    Refiner refiner;
    template <typename Configure>
    Refinement(const Heightfield& field, const EarthShape& earth, Configure&& configure) {
        mesh.reset(field, Embedding::Exact);
        refiner.attach(mesh, field);
        refiner.settings().earth = earth;
        configure(refiner);
        for (int32_t n = 0; n < 200 && !refiner.update().converged; ++n) {
        }
    }
};

// Every sample inside the frustum against the drawn surface, on screen: the samples and the
// mesh's vertices drawn on the curved Earth, the triangles straight between the vertices.
// frontOnly: the samples under drawn triangles that face the eye only (back-face culling leaves
// the others coarse: they cannot be seen).
double worstPixelsOnTheCurvedEarth(const HexMesh& mesh, const Heightfield& field, const EarthShape& earth, const View& view,
                                   int64_t& samplesInView, bool frontOnly = false) {
    auto project = [&](const glm::dvec3& p, double& px, double& py) {
        const glm::dvec3 d = p - view.eye;
        const double z = glm::dot(d, view.forward);
        if (z < view.nearPlane) return false;
        const double tx = glm::dot(d, view.right) / z, ty = glm::dot(d, view.up) / z;
        px = tx * view.pixelsPerTangent, py = ty * view.pixelsPerTangent;
        return std::abs(tx) <= view.tanHalfX && std::abs(ty) <= view.tanHalfY;
    };
    double worst = 0.0;
    samplesInView = 0;
    const double sx = field.scale().spacingX, sy = field.scale().spacingY;
    test::forEachSampleUnderTriangles(mesh, field, true, [&](const glm::dvec3 (&v)[3], int32_t j, int32_t i, const double (&w)[3]) {
        double sxPx, syPx, mxPx = 0.0, myPx = 0.0;
        if (!project(curvedPosition(earth, j * sx, field.heightAt(j, i), i * sy), sxPx, syPx)) return;
        ++samplesInView;
        glm::dvec3 drawn(0.0), corner[3]; // the straight triangle between the curved vertices
        for (int32_t k = 0; k < 3; ++k) corner[k] = curvedPosition(earth, v[k].x, v[k].y, v[k].z), drawn += w[k] * corner[k];
        if (frontOnly) {
            glm::dvec3 n = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
            if (glm::dot(n, curvedUp(earth, v[0].x, v[0].z)) < 0.0) n = -n;
            if (glm::dot(n, drawn - view.eye) >= 0.0) return; // its back is to the eye
        }
        if (!project(drawn, mxPx, myPx) && !(glm::dot(drawn - view.eye, view.forward) > view.nearPlane)) return;
        worst = std::max(worst, std::hypot(mxPx - sxPx, myPx - syPx));
    });
    return worst;
}

} // namespace

TEST(EarthShape, OnTheCurvedEarthEverySampleInTheFrustumIsWithinTauOfTheDrawnSurface) {
    auto field = continentalField();
    ASSERT_NE(field, nullptr);
    const double w = (field->width() - 1) * 2000.0, h = (field->height() - 1) * 2000.0;
    EarthShape sphereEarth = sphere();
    sphereEarth.originX = 0.5 * w, sphereEarth.originZ = 0.5 * h;
    EarthShape geo = geographic(48.0, 2000.0 / (0.02 * kDeg)); // 0.02 degrees a sample: 10 by 10 degrees
    geo.originX = 0.5 * w, geo.originZ = 0.5 * h;
    for (const EarthShape& earth : {sphereEarth, geo}) {
        // Low and looking level across the field, high and looking down at a corner.
        const struct {
            glm::dvec3 eye, target;
        } flatViews[] = {{{0.2 * w, 6000.0, 0.9 * h}, {0.7 * w, 1000.0, 0.3 * h}}, {{0.8 * w, 400000.0, 0.8 * h}, {0.5 * w, 0.0, 0.4 * h}}};
        for (const auto& v : flatViews) {
            const glm::dvec3 eye = curvedPosition(earth, v.eye.x, v.eye.y, v.eye.z);
            const glm::dvec3 target = curvedPosition(earth, v.target.x, v.target.y, v.target.z);
            View view;
            ASSERT_TRUE(makeView(eye, target, curvedUp(earth, v.eye.x, v.eye.z), kTanHalf60, 16.0 / 9.0, 1080.0, 10.0, 1e8, view));
            for (double tau : {1.0, 4.0}) {
                auto viewed = [&](Refiner& r) { r.settings().tau = tau, r.setView(view); };
                Refinement curved(*field, earth, viewed);
                const HexMesh& mesh = curved.mesh;
                const Refiner& refiner = curved.refiner;
                ASSERT_TRUE(refiner.lastUpdate().converged);
                ASSERT_EQ(mesh.checkInvariants(), nullptr);
                int64_t inView = 0;
                const double worst = worstPixelsOnTheCurvedEarth(mesh, *field, earth, view, inView);
                // The flat refinement of the same view, drawn curved: the curvature it ignores.
                Refinement flat(*field, EarthShape{}, viewed);
                const HexMesh& flatMesh = flat.mesh;
                int64_t ignored = 0;
                const double flatWorst = worstPixelsOnTheCurvedEarth(flatMesh, *field, earth, view, ignored);
                std::printf("earth kind %d, eye %.0f m up, tau %.0f: %lld samples in view, worst %.3f px, %lld triangles "
                            "(flat bound: worst %.3f px, %lld triangles); achieved %.3f px\n",
                            int(earth.kind), v.eye.y, tau, (long long)inView, worst, (long long)mesh.triangleCount(), flatWorst,
                            (long long)flatMesh.triangleCount(), refiner.achievedErrorPixels());
                EXPECT_GT(inView, 1000);
                EXPECT_LE(worst, tau * (1.0 + 1e-6));
                EXPECT_LE(worst, refiner.achievedErrorPixels() * (1.0 + 1e-6) + 1e-9);
            }
        }
    }
}

// View-independent refinement (a maximum error in metres, as `hexlod mesh --max-error` runs it)
// on the curved Earth: every sample's image within that distance of the drawn triangle over it.
TEST(EarthShape, AMaximumErrorHoldsOnTheCurvedEarthAsDrawn) {
    auto field = continentalField();
    ASSERT_NE(field, nullptr);
    const double w = (field->width() - 1) * 2000.0, h = (field->height() - 1) * 2000.0;
    EarthShape geo = geographic(48.0, 2000.0 / (0.02 * kDeg));
    geo.originX = 0.5 * w, geo.originZ = 0.5 * h;
    for (double maxError : {5.0, 50.0}) {
        Refinement refined(*field, geo, [&](Refiner& r) { r.settings().viewIndependent = true, r.settings().maxError = maxError; });
        const HexMesh& mesh = refined.mesh;
        const double sx = field->scale().spacingX, sy = field->scale().spacingY;
        double worst = 0.0;
        test::forEachSampleUnderTriangles(mesh, *field, true, [&](const glm::dvec3 (&v)[3], int32_t j, int32_t i, const double (&w)[3]) {
            glm::dvec3 drawn(0.0);
            for (int32_t k = 0; k < 3; ++k) drawn += w[k] * curvedPosition(geo, v[k].x, v[k].y, v[k].z);
            worst = std::max(worst, glm::length(drawn - curvedPosition(geo, j * sx, field->heightAt(j, i), i * sy)));
        });
        std::printf("max error %.0f m on the curved Earth: worst %.3f m, %lld triangles\n", maxError, worst, (long long)mesh.triangleCount());
        EXPECT_LE(worst, maxError * (1.0 + 1e-6));
        EXPECT_GT(worst, 0.2 * maxError) << "the bound is not loose by more than five times";
    }
}

// §5's back-face test on the curved Earth: the slope box's normals drawn through the map and
// allowed the surface's turn. Low over the Grand Canyon (its own 61.7 m samples, a 31 km field)
// looking across it, on the plane, on the sphere and on the ellipsoid at 36° N: the test leaves
// about as many back faces coarse as it does on the plane, and still every sample under a drawn
// triangle that faces the eye is within tau.
TEST(EarthShape, BackFacesAreLeftCoarseOnTheCurvedEarthAndOnlyThey) {
    auto field = test::loadFixture(test::kGrandCanyon);
    ASSERT_NE(field, nullptr);
    const double sx = field->scale().spacingX, w = (field->width() - 1) * sx, h = (field->height() - 1) * sx;
    EarthShape sphereEarth = sphere();
    sphereEarth.originX = 0.5 * w, sphereEarth.originZ = 0.5 * h;
    EarthShape geo = geographic(36.0, sx / (kDeg / 1800.0)); // 2" samples
    geo.originX = 0.5 * w, geo.originZ = 0.5 * h;
    int64_t flatSaving = 0;
    for (const EarthShape& earth : {EarthShape{}, sphereEarth, geo}) {
        const glm::dvec3 flatEye{0.5 * w, 2600.0, 0.95 * h}, flatTarget{0.5 * w, 1500.0, 0.2 * h};
        View view;
        ASSERT_TRUE(makeView(curvedPosition(earth, flatEye.x, flatEye.y, flatEye.z), curvedPosition(earth, flatTarget.x, flatTarget.y, flatTarget.z),
                             curvedUp(earth, flatEye.x, flatEye.z), kTanHalf60, 16.0 / 9.0, 1080.0, 1.0, 1e7, view));
        int64_t triangles[2] = {0, 0};
        for (const bool culling : {false, true}) {
            Refinement lod(*field, earth, [&](Refiner& r) {
                r.settings().tau = 1.0, r.settings().backfaceCulling = culling;
                r.setView(view);
            });
            ASSERT_TRUE(lod.refiner.lastUpdate().converged);
            triangles[culling] = lod.mesh.triangleCount();
            if (!culling) continue;
            int64_t inView = 0;
            const double worst = worstPixelsOnTheCurvedEarth(lod.mesh, *field, earth, view, inView, true);
            std::printf("earth kind %d: %lld triangles without the back-face test, %lld with; front-facing samples worst %.3f px (%lld)\n",
                        int(earth.kind), (long long)triangles[0], (long long)triangles[1], worst, (long long)inView);
            EXPECT_GT(inView, 100000);
            EXPECT_LE(worst, 1.0 + 1e-6);
        }
        const int64_t saving = triangles[0] - triangles[1];
        if (earth.flat()) {
            flatSaving = saving;
            EXPECT_GT(saving, 300) << "a view with back faces";
        } else {
            EXPECT_GE(double(saving), 0.8 * double(flatSaving)) << "earth kind " << int(earth.kind);
        }
    }
}
