// Atmospheric scattering after Hoffman & Preetham 2002, "Rendering Outdoor Light Scattering in
// Real Time", as the paper uses it (§7, ref. [19]): what reaches the eye from a point at
// distance s is L0 * Fex(s) + Lin(s, θ), with Fex = exp(-(βR + βM) s) and
// Lin = (βR ΦR(θ) + βM ΦM(θ)) / (βR + βM) * Esun * (1 - Fex), θ the angle between the view ray
// and the sun. Here the air thins with height (density exp(-h / H), one scale height for the
// Rayleigh and one for the Mie part), so βR s and βM s become optical depths along the ray;
// the sun's own light is dimmed and reddened by the air mass of its path (Kasten & Young
// 1989). Shared by the terrain's vertex stage (per vertex, interpolated) and the sky.

uniform vec3 uBetaRayleigh;  // 1/m at sea level, per RGB wavelength
uniform vec3 uBetaMie;       // 1/m at sea level
uniform vec2 uScaleHeight;   // m: Rayleigh, Mie
uniform float uMieG;         // Henyey-Greenstein asymmetry of the haze
uniform vec3 uSunDirection;  // unit vector towards the sun (drawn space: x east, y up, z south)
uniform vec3 uSunIrradiance; // the sun's light above the atmosphere
uniform float uSunAirMass;   // relative air mass of the sun's path at sea level (1 at the zenith)

const float PI = 3.14159265;
// Hoffman & Preetham scale the in-scattered light by a free factor; single scattering alone
// leaves the sky too dark next to sunlit ground (multiple scattering and the ground's light
// are missing).
const float INSCATTER_GAIN = 2.0;

float phaseRayleigh(float cosTheta) {
    return 3.0 / (16.0 * PI) * (1.0 + cosTheta * cosTheta);
}

float phaseMie(float cosTheta) {
    float g = uMieG;
    return (1.0 - g) * (1.0 - g) / (4.0 * PI * pow(1.0 + g * g - 2.0 * g * cosTheta, 1.5));
}

// Optical depth factor (metres of sea-level air) of a straight path of length s from height a to
// height b through air of density exp(-h / H).
float airPath(float a, float b, float s, float H) {
    a = max(a, 0.0);
    b = max(b, 0.0);
    float ea = exp(-a / H);
    if (abs(b - a) < 1.0) return s * ea;
    return s * H * (ea - exp(-b / H)) / (b - a);
}

// Relative air mass towards elevation sin(e) = mu (Kasten & Young), finite at the horizon.
float airMass(float mu) {
    float zenithDeg = degrees(acos(clamp(mu, 0.0, 1.0)));
    return 1.0 / (max(mu, 0.0) + 0.50572 * pow(max(96.07995 - zenithDeg, 1e-3), -1.6364));
}

// The sun's light at height h (metres above sea level) after its path through the air above.
vec3 sunlightAt(float h) {
    h = max(h, 0.0);
    vec3 depth = uBetaRayleigh * uScaleHeight.x * exp(-h / uScaleHeight.x) + uBetaMie * uScaleHeight.y * exp(-h / uScaleHeight.y);
    return uSunIrradiance * exp(-depth * uSunAirMass);
}

// Extinction Fex and in-scattering Lin of a ray with optical depths (metres of sea-level air)
// depthR, depthM, seen at angle cosTheta from the sun, lit by `sunlight`.
void scatter(float depthR, float depthM, float cosTheta, vec3 sunlight, out vec3 extinction, out vec3 inscatter) {
    vec3 tauR = uBetaRayleigh * depthR, tauM = uBetaMie * depthM;
    vec3 tau = tauR + tauM;
    extinction = exp(-tau);
    vec3 ratio = (tauR * phaseRayleigh(cosTheta) + tauM * phaseMie(cosTheta)) / max(tau, vec3(1e-12));
    inscatter = INSCATTER_GAIN * ratio * sunlight * (1.0 - extinction);
}
