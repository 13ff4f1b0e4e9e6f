// The end-of-run report: per format the inputs, how many were refused cleanly and accepted,
// the failures by kind, the time taken and the rate; then each kind of failure once, with
// how many cases showed it and the first case's id.

const pad = (s, n) => String(s).padStart(n);

export function formatReport({ counts, failures, saved }, { seed }) {
  const lines = [];
  const header = ['format', 'inputs', 'refused', 'accepted', 'crashes', 'hangs', 'blow-ups', 'insane', 'time s', 'cases/s', 'slowest ms', 'refusal kinds'];
  const widths = header.map((h) => Math.max(h.length, 7));
  lines.push(header.map((h, i) => pad(h, widths[i])).join(' '));
  const total = { inputs: 0, refused: 0, accepted: 0, crash: 0, hang: 0, blowup: 0, insane: 0, ms: 0 };
  for (const [format, c] of Object.entries(counts)) {
    for (const k of Object.keys(total)) total[k] += c[k];
    lines.push([format, c.inputs, c.refused, c.accepted, c.crash, c.hang, c.blowup, c.insane, (c.ms / 1000).toFixed(1),
      (c.inputs / (c.ms / 1000 || 1)).toFixed(0), c.slowestMs.toFixed(0), c.refusals.size].map((v, i) => pad(v, widths[i])).join(' '));
  }
  lines.push(['all', total.inputs, total.refused, total.accepted, total.crash, total.hang, total.blowup, total.insane,
    (total.ms / 1000).toFixed(1), (total.inputs / (total.ms / 1000 || 1)).toFixed(0), '', ''].map((v, i) => pad(v, widths[i])).join(' '));
  const groups = new Map();
  for (const f of failures) {
    const key = `${f.id.split(':')[0]} ${f.kind}: ${f.signature}`;
    const g = groups.get(key) ?? { count: 0, first: f };
    g.count++;
    groups.set(key, g);
  }
  const slow = Object.values(counts).filter((c) => c.slowestMs > 1000);
  if (slow.length) lines.push('', `slowest cases (over 1 s, not failures): ${slow.map((c) => `${c.slowestId} ${(c.slowestMs / 1000).toFixed(1)} s`).join(', ')}`);
  if (groups.size) {
    lines.push('', `failures (seed ${seed}), each kind once:`);
    for (const [key, g] of groups) {
      const dir = saved.find((s) => s.id === g.first.id)?.dir;
      lines.push(`  ${g.count} x ${key}`, `      first ${g.first.id}: ${g.first.detail}`, ...(dir ? [`      reproducer ${dir}`] : []));
    }
  } else {
    lines.push('', 'no failures');
  }
  return lines.join('\n');
}
