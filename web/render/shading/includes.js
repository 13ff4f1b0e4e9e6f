// Shader composition: a line `#include "name"` is replaced by the source of that file (one
// level deep is all shaders/ needs; a file is included at most once per program, so two files
// may include the same uniforms).

/**
 * @param {string} source GLSL with `#include "file"` lines
 * @param {Record<string, string>} files sources by file name
 */
export function resolveIncludes(source, files) {
  const seen = new Set();
  return source.replace(/^[ \t]*#include\s+"([^"]+)"[ \t]*$/gm, (_, name) => {
    if (!(name in files)) throw new Error(`shader include "${name}" is unknown`);
    if (seen.has(name)) return `// ${name} already included`;
    seen.add(name);
    return `// ---- ${name}\n${files[name]}\n// ---- end of ${name}`;
  });
}
