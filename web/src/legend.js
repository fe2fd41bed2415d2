// The picture's legend (docs/web.md "The legend"): what view.js draws, each with a swatch in the
// colours it draws with (the core's `picture`, the coin shader's and view.js's), so that the legend
// cannot describe another picture.
import { element } from './controls.js';
import { formatG } from './units.js';
import { kCoinColours, kContactColour, kShadowColour } from './view.js';

// The sRGB encoding the shaders end with (shaders/coin.frag toSrgb), for a linear colour as a CSS one.
const toSrgb = (linear) => (linear <= 0.0031308 ? 12.92 * linear : 1.055 * Math.pow(linear, 1 / 2.4) - 0.055);

// CSS colours: `srgb` as the trace and flat shaders write it out; `linear` an albedo, encoded as the
// coin shader encodes its result (unlit here).
const css = (srgb, alpha = 1) => `rgb(${Array.from(srgb, (c) => Math.round(255 * c)).join(' ')} / ${alpha})`;
const withAlpha = ([r, g, b, alpha]) => css([r, g, b], alpha);
const encoded = (linear) => css(Array.from(linear, toSrgb));

// A swatch: background layers over the floor's colour, as the trace, marker and shadow lie on it.
function swatch(layers, floorColour, kind = 'bar') {
  const background = [...layers, floorColour].join(', ');
  return element('span', { class: `swatch ${kind}`, 'aria-hidden': 'true', style: `background: ${background}` });
}

// One colour as a background layer: every layer but the last must be an image.
const flatLayer = (colour) => `linear-gradient(${colour}, ${colour})`;

// The trace's colour from oldest to newest, with its opacity (shaders/trace.frag: mixed by age).
function ageGradient(recent, old, [recentOpacity, oldOpacity]) {
  return `linear-gradient(to right, ${css(old, oldOpacity)}, ${css(recent, recentOpacity)})`;
}

// A face's metal with a stroke of its enamel.
const face = (metal, enamel) =>
  element('span', { style: `background: ${encoded(metal)}; color: ${encoded(enamel)}`, text: '━' });

const centimetres = (metres) => `${formatG(100 * metres, 3)} cm`;

export class Legend {
  // `picture`: what the picture is drawn in (the core's `picture`: sky, floor, trace colours, grid).
  constructor(container, picture) {
    const t = picture.trace, grid = encoded(picture.floor.minorLine), floor = encoded(picture.floor.floor);
    const on = (layers, kind) => swatch(layers, floor, kind);
    this.grid = element('span');
    const item = (mark, ...text) => element('li', {}, [mark, element('span', {}, text)]);
    const list = element('ul', {}, [
      item(on([ageGradient(t.recentRolling, t.oldRolling, t.opacity)]),
           element('b', { text: 'Trace' }), ': the path of the contact point on the floor so far, orange-red where ' +
           'the coin touches now, fading to blue towards the start.'),
      item(on([ageGradient(t.recentSliding, t.oldSliding, t.opacity)]),
           'Yellow fading to green where the coin slid (with ', element('code', { text: 'sliding' }),
           '); no trace in the air.'),
      item(on([`radial-gradient(circle, ${withAlpha(kContactColour)} 55%, transparent 60%)`], 'dot'),
           element('b', { text: 'Marker' }), ': the contact point now.'),
      item(on([flatLayer(withAlpha(kShadowColour))], 'dot'),
           element('b', { text: 'Shadow' }), ': the coin\'s, cast along the light.'),
      item(on([`repeating-linear-gradient(to right, ${grid} 0 1px, transparent 1px 6px)`]),
           element('b', { text: 'Floor grid' }), `: thin lines every ${centimetres(picture.gridMetres)}, bold every ` +
           `${centimetres(picture.tileMetres)}`, this.grid, '.'),
      item(element('span', { class: 'swatch faces', 'aria-hidden': 'true' }, [
        face(kCoinColours.brass, kCoinColours.blueEnamel), face(kCoinColours.silver, kCoinColours.redEnamel)]),
           element('b', { text: 'Coin' }), ': its +Z face (heads) brass with blue enamel, its back silver with red. ' +
           'Each carries twelve hour ticks, an enamel bar along the coin\'s X axis and an enamel dot, so that its ' +
           'turn ψ and the face up read at a glance; the rim is knurled.'),
    ]);
    container.append(element('summary', { text: 'Legend' }), list);
  }

  // The grid against the coin of the run on screen, whose radius is the seed's unit of length.
  show(scene, units) {
    this.grid.textContent = units.seed ? ` (1 cm = ${formatG(units.shown(0.01, 'm'), 3)} a)`
      : ` (the coin's radius a = ${centimetres(scene.coin.radius)})`;
  }
}
