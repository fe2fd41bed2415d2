// The floor's grid tile (src/render/floor_tile.cpp) and the colours of the classic theme
// (src/render/theme.cpp), which the page draws in: 10 cm tiles with thin lines every centimetre,
// lit and in sRGB, repeated and mipmapped by the sampler.

export const kFloorTileMetres = 0.10;
export const kFloorGridMetres = 0.01;
const kMinorWidth = 0.0005, kMajorWidth = 0.0012;

export const kClassic = {
  backgroundSrgb: [0.86, 0.89, 0.93],
  floor: { floor: [0.25, 0.26, 0.28], minorLine: [0.35, 0.36, 0.38], majorLine: [0.45, 0.47, 0.50] },
  trace: { recentRolling: [0.93, 0.33, 0.08], oldRolling: [0.30, 0.52, 0.95], recentSliding: [0.98, 0.84, 0.10],
           oldSliding: [0.55, 0.90, 0.55], opacity: [0.95, 0.25] },
};

export const toSrgb = (linear) => (linear <= 0.0031308 ? 12.92 * linear : 1.055 * Math.pow(linear, 1 / 2.4) - 0.055);

function lineCoverage(x0, step, spacing, width) {
  const nearest = Math.round((x0 + 0.5 * step) / spacing) * spacing;
  const lo = Math.max(x0, nearest - 0.5 * width), hi = Math.min(x0 + step, nearest + 0.5 * width);
  return Math.max(0, hi - lo) / step;
}

// RGBA bytes of a `pixels` x `pixels` tile; texel (i, j) covers floor [i, i+1) x [j, j+1) * tile / pixels.
export function floorTile(pixels, colours) {
  const rgba = new Uint8Array(4 * pixels * pixels);
  const step = kFloorTileMetres / pixels;
  const coverage = (spacing, width) => Float32Array.from({ length: pixels }, (_, i) => lineCoverage(i * step, step, spacing, width));
  const minor = coverage(kFloorGridMetres, kMinorWidth), major = coverage(kFloorTileMetres, kMajorWidth);
  for (let j = 0; j < pixels; ++j) {
    for (let i = 0; i < pixels; ++i) {
      const mi = minor[i] + minor[j] - minor[i] * minor[j], ma = major[i] + major[j] - major[i] * major[j];
      const p = 4 * (j * pixels + i);
      for (let c = 0; c < 3; ++c) {
        const withMinor = colours.floor[c] + (colours.minorLine[c] - colours.floor[c]) * mi;
        const linear = withMinor + (colours.majorLine[c] - withMinor) * ma;
        rgba[p + c] = Math.round(255 * Math.min(1, Math.max(0, toSrgb(linear))));
      }
      rgba[p + 3] = 255;
    }
  }
  return rgba;
}
