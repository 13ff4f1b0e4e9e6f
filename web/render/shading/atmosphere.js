// The constants of the atmospheric scattering (shaders/scattering.glsl, after Hoffman &
// Preetham 2002, paper §7) and what is computed once per frame on the CPU: the sun's
// direction from its azimuth and elevation, the air mass of its path, and the sky light that
// lights the ground from above. Allocation-free after construction.

/** Rayleigh scattering of sea-level air at 680, 550 and 440 nm, 1/m. */
export const BETA_RAYLEIGH = [5.8e-6, 13.5e-6, 33.1e-6];
/** Mie scattering of a light haze, 1/m (nearly grey). */
export const BETA_MIE = [5e-6, 5.2e-6, 5.5e-6];
/** Scale heights of the air (Rayleigh) and the haze (Mie), metres. */
export const SCALE_HEIGHTS = [8000, 1200];
export const MIE_G = 0.76;
/**
 * The sun above the atmosphere, in the renderer's radiance units, white-balanced as the eye
 * is: the noon sun at sea level, after a zenith path through the air, is white (1, 1, 1).
 */
export const SUN_IRRADIANCE = [0, 1, 2].map((c) => Math.exp(BETA_RAYLEIGH[c] * SCALE_HEIGHTS[0] + BETA_MIE[c] * SCALE_HEIGHTS[1]));
/** Exposure of the tone curve 1 - exp(-k L). */
export const EXPOSURE = 3.0;

/** Relative air mass towards an elevation of sin(e) = mu (Kasten & Young 1989). */
export function airMass(mu) {
  const zenithDeg = (Math.acos(Math.min(Math.max(mu, 0), 1)) * 180) / Math.PI;
  return 1 / (Math.max(mu, 0) + 0.50572 * Math.pow(Math.max(96.07995 - zenithDeg, 1e-3), -1.6364));
}

export class Atmosphere {
  constructor() {
    this.sunDirection = new Float32Array(3); // towards the sun: x east, y up, z south
    this.sunAirMass = 1;
    this.skyLight = new Float32Array(3);     // irradiance of the sky on level ground, per RGB
    this.setSun(250, 25);
  }

  /**
   * @param {number} azimuthDeg compass direction of the sun: 0 north, 90 east, 180 south, 270 west
   * @param {number} elevationDeg angle above the horizon
   */
  setSun(azimuthDeg, elevationDeg) {
    const a = (azimuthDeg * Math.PI) / 180, e = (elevationDeg * Math.PI) / 180;
    this.sunDirection[0] = Math.cos(e) * Math.sin(a);
    this.sunDirection[1] = Math.sin(e);
    this.sunDirection[2] = -Math.cos(e) * Math.cos(a);
    this.sunAirMass = airMass(Math.sin(e));
    // Sky light: the part of the sunlight the air scatters, arriving from the whole sky. The
    // Rayleigh share makes it blue; it dims as the sun sinks and its light crosses more air.
    const sinE = Math.max(Math.sin(e), 0);
    for (let c = 0; c < 3; ++c) {
      const depth = BETA_RAYLEIGH[c] * SCALE_HEIGHTS[0] + BETA_MIE[c] * SCALE_HEIGHTS[1];
      const sunlight = SUN_IRRADIANCE[c] * Math.exp(-depth * this.sunAirMass * 0.5);
      const scattered = 1 - Math.exp(-(BETA_RAYLEIGH[c] * SCALE_HEIGHTS[0] * 2.5 + BETA_MIE[c] * SCALE_HEIGHTS[1]));
      this.skyLight[c] = 0.45 * sunlight * scattered * (0.25 + 0.75 * Math.sqrt(sinE));
    }
  }
}
