// Compiles and links a WebGL2 program, and looks up its uniforms: for the terrain, the sky and
// the overlays. A failure throws with the driver's log, named by `what`; a lost context is not
// a failure (everything is made again when it comes back).

function compile(gl, type, source, what) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS) && !gl.isContextLost()) {
    throw new Error(`${what} shader compile failed: ${gl.getShaderInfoLog(shader)}`);
  }
  return shader;
}

/**
 * @param {WebGL2RenderingContext} gl
 * @param {string} vertex GLSL source, includes resolved
 * @param {string} fragment
 * @param {string} what the program's name in an error message
 * @returns {WebGLProgram}
 */
export function linkProgram(gl, vertex, fragment, what) {
  const program = gl.createProgram();
  gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, vertex, what));
  gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, fragment, what));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS) && !gl.isContextLost()) {
    throw new Error(`${what} shader link failed: ${gl.getProgramInfoLog(program)}`);
  }
  return program;
}

/** The locations of `names` in `program`, by name. */
export function uniformLocations(gl, program, names) {
  return Object.fromEntries(names.map((name) => [name, gl.getUniformLocation(program, name)]));
}
