// The units the page shows numbers in (docs/web.md "Units"): SI, as the scene file holds them, or the
// seed's dimensionless units M = a = g = 1 (docs/seed.md), in which a student reads the write-up's
// numbers off the page (ω_c = 1/√3 for the thin disk). Only the display changes: the scene stays SI,
// and a number typed in the seed's units is multiplied back into SI before the core sees it.
import { defaultOf } from './schema.js';

// An SI unit as [mass, length, time] exponents, and the seed's unit of that dimension: with the unit of
// time √(a/g), kg^α m^β s^γ becomes M^α a^β (a/g)^(γ/2). Units not listed (degrees, none) read the same
// in both systems.
const kDimensions = new Map([
  ['kg', [1, 0, 0, 'M']],
  ['m', [0, 1, 0, 'a']],
  ['s', [0, 0, 1, '√(a/g)']],
  ['rad/s', [0, 0, -1, '√(g/a)']],
  ['1/s', [0, 0, -1, '√(g/a)']],
  ['1/s^2', [0, 0, -2, 'g/a']],
  ['m/s', [0, 1, -1, '√(ga)']],
  ['m/s^2', [0, 1, -2, 'g']],
  ['kg m^2', [1, 2, 0, 'Ma²']],
  ['kg/m^3', [1, -3, 0, 'M/a³']],
  ['Pa s', [1, -1, -1, 'M√(g/a)/a']],
  ['N', [1, 1, -2, 'Mg']],
  ['J', [1, 2, -2, 'Mga']],
  ['W', [1, 2, -3, 'Mg√(ga)']],
]);

// The keys that fix the seed's units: they show in SI in either system (in the seed's they would read 1).
export const kUnitKeys = new Set(['coin.mass', 'coin.radius', 'gravity']);

const pretty = (unit) => unit.replace('^2', '²').replace('^3', '³');

export class Units {
  // `system`: 'si' or 'seed'; `basis`: the coin's {M, a, g} in kg, m and m/s², the seed's units.
  constructor(system, basis) {
    this.seed = system === 'seed';
    this.basis = basis;
  }

  // SI units per shown unit: 1 in SI, M^α a^β (a/g)^(γ/2) in the seed's.
  scale(unit) {
    const dimension = kDimensions.get(unit);
    if (!this.seed || !dimension) return 1;
    const { M, a, g } = this.basis;
    const [mass, length, time] = dimension;
    return Math.pow(M, mass) * Math.pow(a, length) * Math.pow(a / g, time / 2);
  }

  label(unit) {
    const dimension = kDimensions.get(unit);
    return this.seed && dimension ? dimension[3] : pretty(unit || '');
  }

  shown(value, unit) {
    return value / this.scale(unit);
  }

  toSI(value, unit) {
    return value * this.scale(unit);
  }
}

// The seed's units of a scene: its coin's mass and radius and its gravity (the schema's default where
// the scene gives none).
export function basisOf(scene) {
  const g = scene.gravity !== undefined ? scene.gravity : defaultOf('gravity');
  return { M: scene.coin.mass, a: scene.coin.radius, g };
}

// C's %.Ng (as fmt's {:.Ng}), the form the program prints: N significant digits, trailing zeros
// dropped, an exponent below 1e-4 and from 10^N.
export function formatG(value, digits) {
  if (value === Infinity) return '∞';
  if (value === 0) return '0';
  const exponent = Number(value.toExponential(digits - 1).split('e')[1]);
  const trim = (text) => (text.includes('.') ? text.replace(/\.?0+$/, '') : text);
  if (exponent < -4 || exponent >= digits) {
    const [mantissa, power] = value.toExponential(digits - 1).split('e');
    return `${trim(mantissa)}e${power.replace('+', '')}`;
  }
  return trim(value.toFixed(digits - 1 - exponent));
}
