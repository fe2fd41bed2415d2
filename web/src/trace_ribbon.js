// The trace ribbon as the renderer builds it (src/render/meshes.cpp ribbonStrip), with its width left
// to the page's shader, which scales it with the view as the renderer does with the picture. The coin
// itself comes from the core's visual track, the renderer's own triangles.

// The CSV's phase of a coin in the air (docs/contract.md §6a), and the mark its trace points carry
// (src/render/meshes.h kTraceInTheAir): the trace shader draws nothing there.
export const kPhaseFlight = 2;
export const kTraceInTheAir = 2;

// The trace as a triangle strip along the contact points (meshes.cpp ribbonStrip), with the width
// left to the shader: per vertex the point, its unit side (+ or -), its index in the trace (the
// shader turns it into an age) and whether the coin slid there. Consecutive points closer than
// 0.1 µm are one point.
export function ribbonStrip(xs, zs, slides, count, phases) {
  const kept = [];
  for (let i = 0; i < count; ++i) {
    if (kept.length === 0) { kept.push(i); continue; }
    const j = kept[kept.length - 1];
    if (Math.hypot(xs[i] - xs[j], zs[i] - zs[j]) > 1e-7) kept.push(i);
  }
  const n = kept.length < 2 ? 0 : kept.length;
  const point = new Float32Array(4 * n), side = new Float32Array(4 * n), index = new Float32Array(2 * n), sliding = new Float32Array(2 * n);
  for (let k = 0; k < n; ++k) {
    const b = kept[Math.max(k - 1, 0)], a = kept[Math.min(k + 1, n - 1)], i = kept[k];
    let tx = xs[a] - xs[b], tz = zs[a] - zs[b];
    const length = Math.hypot(tx, tz);
    tx /= length; tz /= length;
    for (let s = 0; s < 2; ++s) {
      const v = 2 * k + s, sign = s === 0 ? 1 : -1;
      point[2 * v] = xs[i]; point[2 * v + 1] = zs[i];
      side[2 * v] = -tz * sign; side[2 * v + 1] = tx * sign;
      index[v] = i;
      sliding[v] = phases && phases[i] === kPhaseFlight ? kTraceInTheAir : slides && slides[i] ? 1 : 0;
    }
  }
  return { point, side, index, sliding, vertices: 2 * n };
}
