// WebGL2 renderer of the hexagon mesh's fan stream (paper §7). It only uploads and draws
// arrays the core filled; it computes no geometry. Attribute locations match the layout()
// qualifiers in shaders/.
import vertexSource from '../shaders/terrain.vert?raw';
import fragmentSource from '../shaders/terrain.frag?raw';

export const ATTRIB_POSITION = 0;
export const ATTRIB_NORMAL = 1;
const FLOATS_PER_VERTEX = 6; // x, y, z, nx, ny, nz (src/fan_stream.h kFloatsPerVertex)
const SKY_COLOR = [0.62, 0.74, 0.88];
const OUTLINE_COLOR = [0.08, 0.09, 0.12, 0.55];
const UNIFORMS = ['uViewProjection', 'uCameraPosition', 'uSunDirection', 'uHeightRange', 'uSkyColor',
  'uFogDistance', 'uTint', 'uTintAmount', 'uExtent', 'uLineColor'];

function compile(gl, type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
    throw new Error(`shader compile failed: ${gl.getShaderInfoLog(shader)}`);
  }
  return shader;
}

function link(gl, vertex, fragment) {
  const program = gl.createProgram();
  gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, vertex));
  gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, fragment));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
    throw new Error(`shader link failed: ${gl.getProgramInfoLog(program)}`);
  }
  return program;
}

/** A colour per level: hues far apart around the wheel, semi-hexagons (odd levels) darker. */
function levelColor(level) {
  const hue = ((level >> 1) * 137) % 360;
  const lightness = level % 2 ? 0.4 : 0.55;
  const a = 0.9 * Math.min(lightness, 1 - lightness);
  const channel = (n) => {
    const k = (n + hue / 30) % 12;
    return lightness - a * Math.max(-1, Math.min(k - 3, 9 - k, 1));
  };
  return [channel(0), channel(8), channel(4)];
}

export class TerrainRenderer {
  /** @param {WebGL2RenderingContext} gl */
  constructor(gl) {
    this.gl = gl;
    this.program = link(gl, vertexSource, fragmentSource);
    this.uniforms = Object.fromEntries(UNIFORMS.map((name) => [name, gl.getUniformLocation(this.program, name)]));
    this.vertexBuffer = gl.createBuffer();
    this.fanBuffer = gl.createBuffer();
    this.outlineBuffer = gl.createBuffer();
    this.fanVao = this.makeVao(this.fanBuffer);
    this.outlineVao = this.makeVao(this.outlineBuffer);
    this.levelOffsets = [];
    this.outlineCount = 0;
    this.heightRange = [0, 1];
    this.extent = [0, 0];
    this.sunDirection = normalize([-0.55, 0.55, -0.35]);
  }

  makeVao(indexBuffer) {
    const gl = this.gl;
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.vertexBuffer);
    const stride = FLOATS_PER_VERTEX * 4;
    gl.enableVertexAttribArray(ATTRIB_POSITION);
    gl.vertexAttribPointer(ATTRIB_POSITION, 3, gl.FLOAT, false, stride, 0);
    gl.enableVertexAttribArray(ATTRIB_NORMAL);
    gl.vertexAttribPointer(ATTRIB_NORMAL, 3, gl.FLOAT, false, stride, 12);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, indexBuffer);
    gl.bindVertexArray(null);
    return vao;
  }

  /**
   * Uploads a fan stream (see Terrain.buildStream) and what the shading needs to know.
   * @param {number} minHeight @param {number} maxHeight drawn height range, metres
   * @param {number} extentX @param {number} extentZ the field's rectangle, metres
   */
  setStream(stream, minHeight, maxHeight, extentX, extentZ) {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.vertexBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, stream.vertices, gl.STATIC_DRAW);
    gl.bindVertexArray(this.fanVao);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, stream.indices, gl.STATIC_DRAW);
    gl.bindVertexArray(this.outlineVao);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, stream.outline, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    this.levelOffsets = Array.from(stream.levelOffsets);
    this.outlineCount = stream.outline.length;
    this.heightRange = [minHeight, maxHeight];
    this.extent = [extentX, extentZ];
  }

  /**
   * Draws the terrain seen by an OrbitCamera whose matrices are up to date.
   * @param {{colorByLevel?: boolean, outline?: boolean}} view
   */
  draw(camera, width, height, view = {}) {
    const gl = this.gl;
    gl.viewport(0, 0, width, height);
    gl.clearColor(SKY_COLOR[0], SKY_COLOR[1], SKY_COLOR[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    const total = this.levelOffsets.at(-1) ?? 0;
    if (total === 0) return;
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.CULL_FACE);
    gl.useProgram(this.program);
    const u = this.uniforms;
    gl.uniformMatrix4fv(u.uViewProjection, false, camera.viewProjection);
    gl.uniform3fv(u.uCameraPosition, camera.position);
    gl.uniform3fv(u.uSunDirection, this.sunDirection);
    gl.uniform2f(u.uHeightRange, this.heightRange[0], this.heightRange[1]);
    gl.uniform3fv(u.uSkyColor, SKY_COLOR);
    gl.uniform1f(u.uFogDistance, camera.distance * 8);
    gl.uniform2f(u.uExtent, this.extent[0], this.extent[1]);
    gl.uniform4f(u.uLineColor, 0, 0, 0, 0);
    // Push the surface back a little so the outlines on it are not lost in the depth test.
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 1);
    gl.bindVertexArray(this.fanVao);
    // WebGL2 always restarts primitives at index 0xFFFFFFFF: all fans go out in one call, or
    // one call per level when each level gets its own colour.
    if (view.colorByLevel) {
      gl.uniform1f(u.uTintAmount, 0.45);
      for (let level = 0; level + 1 < this.levelOffsets.length; ++level) {
        const first = this.levelOffsets[level], count = this.levelOffsets[level + 1] - first;
        if (count === 0) continue;
        gl.uniform3fv(u.uTint, levelColor(level));
        gl.drawElements(gl.TRIANGLE_FAN, count, gl.UNSIGNED_INT, first * 4);
      }
    } else {
      gl.uniform1f(u.uTintAmount, 0);
      gl.drawElements(gl.TRIANGLE_FAN, total, gl.UNSIGNED_INT, 0);
    }
    gl.disable(gl.POLYGON_OFFSET_FILL);
    if (view.outline && this.outlineCount > 0) {
      gl.enable(gl.BLEND);
      gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
      gl.uniform4fv(u.uLineColor, OUTLINE_COLOR);
      gl.bindVertexArray(this.outlineVao);
      gl.drawElements(gl.LINES, this.outlineCount, gl.UNSIGNED_INT, 0);
      gl.disable(gl.BLEND);
    }
    gl.bindVertexArray(null);
  }
}

function normalize(v) {
  const l = Math.hypot(...v);
  return v.map((x) => x / l);
}

export { SKY_COLOR, levelColor };
