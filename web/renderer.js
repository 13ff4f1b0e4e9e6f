// WebGL2 renderer of the terrain mesh. It only uploads and draws arrays the core filled; it
// computes no geometry. Attribute locations match the layout() qualifiers in shaders/.
import vertexSource from '../shaders/terrain.vert?raw';
import fragmentSource from '../shaders/terrain.frag?raw';

export const ATTRIB_POSITION = 0;
export const ATTRIB_NORMAL = 1;
const FLOATS_PER_VERTEX = 6; // x, y, z, nx, ny, nz (src/grid_mesh.h MeshVertex)

const SKY_COLOR = [0.62, 0.74, 0.88];

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

export class TerrainRenderer {
  /** @param {WebGL2RenderingContext} gl */
  constructor(gl) {
    this.gl = gl;
    this.program = link(gl, vertexSource, fragmentSource);
    this.uniforms = {};
    for (const name of ['uViewProjection', 'uCameraPosition', 'uSunDirection', 'uHeightRange', 'uSkyColor', 'uFogDistance']) {
      this.uniforms[name] = gl.getUniformLocation(this.program, name);
    }
    this.vao = gl.createVertexArray();
    this.vertexBuffer = gl.createBuffer();
    this.indexBuffer = gl.createBuffer();
    gl.bindVertexArray(this.vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.vertexBuffer);
    const stride = FLOATS_PER_VERTEX * 4;
    gl.enableVertexAttribArray(ATTRIB_POSITION);
    gl.vertexAttribPointer(ATTRIB_POSITION, 3, gl.FLOAT, false, stride, 0);
    gl.enableVertexAttribArray(ATTRIB_NORMAL);
    gl.vertexAttribPointer(ATTRIB_NORMAL, 3, gl.FLOAT, false, stride, 12);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.indexBuffer);
    gl.bindVertexArray(null);
    this.indexCount = 0;
    this.heightRange = [0, 1];
    this.sunDirection = normalize([-0.55, 0.55, -0.35]);
  }

  /** Uploads a mesh: Float32Array of 6 floats per vertex and a Uint32Array triangle list. */
  setMesh(vertices, indices, minHeight, maxHeight) {
    const gl = this.gl;
    gl.bindVertexArray(this.vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.vertexBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, vertices, gl.STATIC_DRAW);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.indexBuffer);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    this.indexCount = indices.length;
    this.heightRange = [minHeight, maxHeight];
  }

  /** Draws the mesh seen by an OrbitCamera whose matrices are up to date. */
  draw(camera, width, height) {
    const gl = this.gl;
    gl.viewport(0, 0, width, height);
    gl.clearColor(SKY_COLOR[0], SKY_COLOR[1], SKY_COLOR[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    if (this.indexCount === 0) return;
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
    gl.bindVertexArray(this.vao);
    gl.drawElements(gl.TRIANGLES, this.indexCount, gl.UNSIGNED_INT, 0);
    gl.bindVertexArray(null);
  }
}

function normalize(v) {
  const l = Math.hypot(...v);
  return v.map((x) => x / l);
}

export { SKY_COLOR };
