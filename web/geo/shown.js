// A value as a message shows it: what a file held where a reader expected something else.

/** A value for a message: numbers as they are, anything else as JSON ("87" for a string). */
export function shown(v) {
  if (typeof v === 'number') return String(v);
  if (Array.isArray(v) || ArrayBuffer.isView(v)) { // a tag's values: the first few, and how many
    const values = Array.from(v.slice(0, 4), (x) => shown(x));
    return v.length <= 4 ? `[${values.join(', ')}]` : `[${values.join(', ')}, … ${v.length} values]`;
  }
  const text = JSON.stringify(v) ?? String(v);
  return text.length > 80 ? `${text.slice(0, 80)}…` : text;
}
