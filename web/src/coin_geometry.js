// The coin and the trace ribbon as the renderer builds them (src/render/meshes.cpp), so that the page
// draws the program's coin: a closed cylinder (an annulus with a hole) whose outer rim is rounded by
// the edge radius, in the body frame (coin plane = body XY, normal = body Z), and the shape as the
// scene loader draws it (src/scene/scene_loader.cpp parseCoin).

// Which surface a vertex belongs to; the coin shader paints each differently (CoinPart).
const kFrontFace = 0, kBackFace = 1, kOuterRim = 2, kInnerRim = 3;
// meshes.cpp: 8 rings per quarter-circle fillet; renderer.cpp: 128 facets round the rim.
const kFilletRings = 8;
export const kCoinSegments = 128;

// The drawn shape of a scene's coin: {radius, innerRadius, thickness, edgeRadius}, m. A coin without
// thickness is the seed's thin coin, drawn 0.06 x radius thick with a sharp rim; with thickness its
// edge radius defaults to the largest that fits; a thin hoop is drawn as a band as wide as it is thick.
export function drawnCoinShape(coin) {
  const radius = coin.radius;
  const thickness = coin.thickness !== undefined ? coin.thickness : 0.06 * radius;
  const ring = coin.shape === 'ring';
  const hole = ring ? (coin.inner_radius !== undefined ? coin.inner_radius : radius) : 0;
  let edgeRadius = 0;
  if (coin.thickness !== undefined) {
    edgeRadius = coin.edge_radius !== undefined ? coin.edge_radius : Math.min(0.5 * thickness, radius - hole);
  }
  const innerRadius = ring ? Math.min(hole, radius - Math.max(thickness, 0.04 * radius)) : 0;
  return { radius, innerRadius, thickness, edgeRadius };
}

// The outer rim's profile in the (r, z) half-plane from the back face's edge to the front face's,
// each point with its outward normal: meshes.cpp outerRimProfile.
function outerRimProfile(shape) {
  const half = 0.5 * shape.thickness, outer = shape.radius, rho = shape.edgeRadius;
  if (!(rho > 0)) return [{ r: outer, z: -half, nr: 1, nz: 0 }, { r: outer, z: half, nr: 1, nz: 0 }];
  const centreR = outer - rho, centreZ = Math.max(0, half - rho);
  const profile = [];
  const fillet = (side, beta0, skipFirst) => {
    for (let k = skipFirst ? 1 : 0; k <= kFilletRings; ++k) {
      const beta = beta0 + 0.5 * Math.PI * k / kFilletRings;
      const c = Math.cos(beta), s = Math.sin(beta);
      let p = { r: centreR + rho * c, z: side * centreZ + rho * s, nr: c, nz: s };
      const atFace = side < 0 ? k === 0 : k === kFilletRings, atBand = side < 0 ? k === kFilletRings : k === 0;
      if (atFace) p = { r: centreR, z: side * half, nr: 0, nz: side };
      if (atBand) p = { r: outer, z: side * centreZ, nr: 1, nz: 0 };
      profile.push(p);
    }
  };
  fillet(-1, -0.5 * Math.PI, false);
  fillet(+1, 0, centreZ === 0);
  return profile;
}

// Triangles of the coin: {position, normal, part} as flat Float32Arrays (meshes.cpp coinTriangles).
export function coinTriangles(shape, segments = kCoinSegments) {
  const half = 0.5 * shape.thickness, outer = shape.radius, inner = shape.innerRadius;
  const faceOuter = outer - shape.edgeRadius;
  const rim = outerRimProfile(shape);
  const position = [], normal = [], part = [];
  const vertex = (p, n, which) => { position.push(p[0], p[1], p[2]); normal.push(n[0], n[1], n[2]); part.push(which); };
  const quad = (a, b, c, d) => { for (const v of [a, b, c, a, c, d]) vertex(...v); };
  const up = [0, 0, 1], down = [0, 0, -1];
  for (let i = 0; i < segments; ++i) {
    const a0 = 2 * Math.PI * i / segments, a1 = 2 * Math.PI * (i + 1) / segments;
    const u0 = [Math.cos(a0), Math.sin(a0)], u1 = [Math.cos(a1), Math.sin(a1)];
    const at = (r, u, z) => [r * u[0], r * u[1], z];
    if (inner > 0) {
      quad([at(inner, u0, half), up, kFrontFace], [at(faceOuter, u0, half), up, kFrontFace],
           [at(faceOuter, u1, half), up, kFrontFace], [at(inner, u1, half), up, kFrontFace]);
      quad([at(inner, u1, -half), down, kBackFace], [at(faceOuter, u1, -half), down, kBackFace],
           [at(faceOuter, u0, -half), down, kBackFace], [at(inner, u0, -half), down, kBackFace]);
      const n0 = [-u0[0], -u0[1], 0], n1 = [-u1[0], -u1[1], 0];
      quad([at(inner, u1, -half), n1, kInnerRim], [at(inner, u0, -half), n0, kInnerRim],
           [at(inner, u0, half), n0, kInnerRim], [at(inner, u1, half), n1, kInnerRim]);
    } else {
      vertex([0, 0, half], up, kFrontFace); vertex(at(faceOuter, u0, half), up, kFrontFace); vertex(at(faceOuter, u1, half), up, kFrontFace);
      vertex([0, 0, -half], down, kBackFace); vertex(at(faceOuter, u1, -half), down, kBackFace); vertex(at(faceOuter, u0, -half), down, kBackFace);
    }
    for (let k = 0; k + 1 < rim.length; ++k) {
      const p = rim[k], q = rim[k + 1];
      quad([at(p.r, u0, p.z), [p.nr * u0[0], p.nr * u0[1], p.nz], kOuterRim],
           [at(p.r, u1, p.z), [p.nr * u1[0], p.nr * u1[1], p.nz], kOuterRim],
           [at(q.r, u1, q.z), [q.nr * u1[0], q.nr * u1[1], q.nz], kOuterRim],
           [at(q.r, u0, q.z), [q.nr * u0[0], q.nr * u0[1], q.nz], kOuterRim]);
    }
  }
  return { position: new Float32Array(position), normal: new Float32Array(normal), part: new Float32Array(part) };
}

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
