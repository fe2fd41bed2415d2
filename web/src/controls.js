// The page's controls, each built from its key in the scene schema (`coinroll schema`): the label is
// the quantity's name and symbol, the tooltip the key with its doc, range and default, the unit its
// unit in the units chosen (units.js); a number gets a slider (on a log scale where its range spans
// decades) and a box for the exact value, a name a menu, a boolean a checkbox; a key without a default
// that may be absent (thickness, friction) gets a checkbox that puts it in the scene or takes it out.
// A control is shown only where the schema's presence rules let its key be on.
import { defaultOf, deletePath, getPath, hasEffect, presenceHolds, schemaKey, setEffect, setPath } from './schema.js';
import { formatG, kUnitKeys, Units } from './units.js';

// What the page offers, in its groups; every range, default, unit and text comes from the schema. The
// list is page.html's, which `coinroll export --controls` reads too: [[title, paths], ...].
export const kGroups = JSON.parse(document.getElementById('coinroll-controls').textContent)
  .map((group) => [group.title, group.keys]);

// Each control's name as a student reads it, with the seed's symbol where it has one (docs/seed.md,
// docs/rim.md); the key itself is in the tooltip.
const kNames = new Map([
  ['coin.shape', 'shape'], ['coin.radius', 'radius a'], ['coin.inner_radius', 'hole radius b'],
  ['coin.I_X', 'moment I_X'], ['coin.I_Z', 'moment I_Z'], ['coin.thickness', 'thickness h'],
  ['coin.edge_radius', 'edge radius ρ'], ['coin.mass', 'mass M'],
  ['initial[steady].steady', 'start'], ['initial.theta', 'tilt θ'], ['initial.phi', 'heading φ'],
  ['initial.omega_X', 'tilt rate ω_X'], ['initial.omega_Y', 'rate ω_Y'], ['initial.omega_Z', 'spin ω_Z'],
  ['initial.x', 'centre x'], ['initial.z', 'centre z'],
  ['initial[steady].theta', 'tilt θ'], ['initial[steady].omega_Z', 'spin ω_Z'], ['initial[steady].branch', 'root f±'],
  ['friction', 'friction μ'], ['friction_static', 'static μ_s'], ['sliding', 'sliding'],
  ['initial.v_x', 'velocity v_x'], ['initial.v_z', 'velocity v_z'],
  ['flight', 'flight'], ['restitution', 'restitution e'], ['impact_friction', 'impact μ'], ['initial.y', 'height y'],
  ['initial.v_y', 'velocity v_y'], ['stop_when_decided', 'stop once decided'],
  ['effects[air_drag]', 'air drag'], ['effects[air_drag].model', 'model'],
  ['effects[air_drag].viscosity', 'air viscosity'], ['effects[air_drag].density', 'air density'],
  ['effects[rolling_resistance]', 'rolling resistance'], ['effects[rolling_resistance].length', 'length'],
  ['effects[spin_friction]', 'spin friction'], ['effects[spin_friction].length', 'length'],
  ['duration', 'duration'], ['gravity', 'gravity g'],
]);

const kSliderSteps = 1000;

// The key's range, in `units` (the scene's SI where not given).
function rangeText(key, units = new Units('si')) {
  const lo = key.minimum, hi = key.maximum;
  const bound = (b) => shownNumber(units.shown(b.value, key.unit), units.scale(key.unit) !== 1);
  if (lo && hi) return `${lo.inclusive ? '[' : '('}${bound(lo)}, ${bound(hi)}${hi.inclusive ? ']' : ')'}`;
  if (lo) return `${lo.inclusive ? '≥' : '>'} ${bound(lo)}`;
  if (hi) return `${hi.inclusive ? '≤' : '<'} ${bound(hi)}`;
  return 'any';
}

// The key, its doc, range and default as the scene file has them, and the seed's unit where shown in it.
function tooltip(key, units) {
  const parts = [`${key.path}: ${key.doc}`, `range ${rangeText(key)}${key.unit ? ` ${key.unit}` : ''}`];
  if (key.default !== undefined) parts.push(`default ${JSON.stringify(key.default)}`);
  else if (key.required) parts.push('required');
  else parts.push('optional: unticked, the key is left out of the scene');
  const scale = units.scale(key.unit);
  if (scale !== 1) parts.push(`shown in units of ${units.label(key.unit)} = ${formatG(scale, 6)} ${key.unit}`);
  else if (units.seed && kUnitKeys.has(key.path)) parts.push('shown in SI: this is one of the seed\'s units M, a, g');
  return parts.join('\n');
}

// deg. The lowest tilt at which a start is refused for lying too near flat (physics/validity.h
// kFlatTilt, the Euler angles' stop; the other formulations stop later). The page does not know which
// formulation a scene runs in, so its tilt sliders stay inside this one: the box still takes more.
const kStartTiltLimit = 89;
const kTiltPaths = new Set(['initial.theta', 'initial[steady].theta']);

// The values a slider may offer, in the units shown (`scale` SI units per shown unit): the schema's
// range, for a tilt also inside the flat stop; `inclusive` false where the bound itself is refused.
function sliderBounds(key, scale) {
  const lo = Object.assign({ value: -Infinity, inclusive: false }, key.minimum);
  const hi = Object.assign({ value: Infinity, inclusive: false }, key.maximum);
  lo.value /= scale;
  hi.value /= scale;
  if (kTiltPaths.has(key.path)) {
    if (lo.value <= -kStartTiltLimit) Object.assign(lo, { value: -kStartTiltLimit, inclusive: false });
    if (hi.value >= kStartTiltLimit) Object.assign(hi, { value: kStartTiltLimit, inclusive: false });
  }
  return { lo, hi };
}

// The slider's span for a value: the range where it is narrow enough to slide through; a log scale
// where it is positive and spans decades (two decades either side of the value, inside the range);
// else a linear window round the value that grows as the value does.
function sliderScale(key, value, scale) {
  const { lo, hi } = sliderBounds(key, scale);
  const v = Number.isFinite(value) ? value : 0;
  let span;
  if (lo.value >= 0 && v > 0 && !(hi.value / Math.max(lo.value, Number.MIN_VALUE) < 100)) {
    span = { log: true, from: Math.max(lo.value > 0 ? lo.value : v * 1e-2, v * 1e-2), to: Math.min(hi.value, v * 1e2) };
  } else if (Number.isFinite(lo.value) && Number.isFinite(hi.value) && hi.value - lo.value <= 1000) {
    span = { log: false, from: lo.value, to: hi.value };
  } else {
    const half = Math.pow(10, Math.ceil(Math.log10(Math.max(Math.abs(v), 1e-9) * 4)));
    const width = Math.max(half, lo.value >= 0 ? 1 : 10);
    span = { log: false, from: Math.max(lo.value, lo.value >= 0 ? 0 : v - width), to: Math.min(hi.value, v + width) };
  }
  // An end on a bound the range excludes moves a slider step inside, rounded inwards to the three
  // digits the slider writes, so that no position of the slider is a value the scene refuses.
  const stepIn = (end, towards) => (span.log ? end * Math.pow(towards / end, 1 / kSliderSteps)
    : end + (towards - end) / kSliderSteps);
  if (!lo.inclusive && span.from <= lo.value) span.from = roundTowards(stepIn(span.from, span.to), +1);
  if (!hi.inclusive && span.to >= hi.value) span.to = roundTowards(stepIn(span.to, span.from), -1);
  return span;
}

// `value` to three significant digits, rounded up (direction +1) or down (-1).
function roundTowards(value, direction) {
  if (value === 0) return 0;
  const unit = Math.pow(10, Math.floor(Math.log10(Math.abs(value))) - 2);
  return Number(((direction > 0 ? Math.ceil(value / unit) : Math.floor(value / unit)) * unit).toPrecision(3));
}

const toSlider = (scale, value) => {
  const f = scale.log ? Math.log(value / scale.from) / Math.log(scale.to / scale.from) : (value - scale.from) / (scale.to - scale.from);
  return Math.round(kSliderSteps * Math.min(1, Math.max(0, f)));
};
// Three significant digits off the slider, so that what it writes into the scene reads cleanly, and
// never past the span's ends: rounding the end's neighbours may not step onto an excluded bound.
const fromSlider = (scale, position) => {
  const f = position / kSliderSteps;
  const value = scale.log ? scale.from * Math.pow(scale.to / scale.from, f) : scale.from + f * (scale.to - scale.from);
  return value === 0 ? 0 : Math.min(scale.to, Math.max(scale.from, Number(value.toPrecision(3))));
};

// Small numbers in exponent form, which a narrow box shows whole (1.8e-5, not 0.000018).
const numberText = (value) => (value !== 0 && Math.abs(value) < 1e-3 ? value.toExponential() : String(value));
// A number as a control shows it: as it is in the scene, or converted to the seed's units to six
// digits, which hides the conversion's round-off (1.2 s / s = 1.2000000000000002).
const shownNumber = (value, converted) =>
  numberText(converted && Number.isFinite(value) ? Number(value.toPrecision(6)) : value);

// A symbol as the seed writes it: ω_Z with its index set below.
export function symbol(text) {
  return text.split(/_(\w)/).map((part, i) => (i % 2 ? element('sub', { text: part }) : part));
}

// A DOM element with its attributes ('text': its text) and children; the page's panels share it.
export function element(tag, attributes = {}, children = []) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attributes)) {
    if (name === 'text') node.textContent = value;
    else node.setAttribute(name, value);
  }
  for (const c of children) node.append(c);
  return node;
}

// One control. `page.scene` is the scene being edited; `page.changed(path)` runs it.
class Control {
  constructor(path, page) {
    Object.assign(this, { path, page });
    const effect = /^effects\[(\w+)\]$/.exec(path);
    this.effect = effect ? effect[1] : null;
    this.key = schemaKey(this.effect ? `${path}.type` : path);
    this.optional = !this.effect && this.key.type !== 'name' && this.key.default === undefined && !this.key.required;
    const whole = this.effect || this.key.type === 'boolean';
    this.row = element('div', { class: whole ? 'control whole' : 'control', 'data-path': path });
    const name = kNames.get(path);
    const label = element('label', { class: 'name' }, symbol(name));
    this.row.append(label);
    const spoken = `${name} (${path})`;
    if (this.effect || this.optional || this.key.type === 'boolean') {
      this.check = element('input', { type: 'checkbox', 'aria-label': `${spoken} on` });
      this.check.addEventListener('change', () => this.onCheck());
      label.prepend(this.check);
    }
    if (this.key.path === 'initial[steady].steady') {
      const starts = ['(rates)', ...this.key.names];
      const options = starts.map((n) => element('option', { value: n, text: n }));
      this.menu = element('select', { 'aria-label': spoken }, options);
      this.menu.addEventListener('change', () => this.onStart());
      this.row.append(this.menu);
    } else if (this.key.type === 'name' && !this.effect) {
      const names = this.key.names.map((n) => element('option', { value: n, text: n }));
      this.menu = element('select', { 'aria-label': spoken }, names);
      this.menu.addEventListener('change', () => this.commit(this.menu.value));
      this.row.append(this.menu);
    } else if (this.key.type === 'number') {
      this.slider = element('input', { type: 'range', min: 0, max: kSliderSteps, step: 1,
                                       'aria-label': `${spoken} slider` });
      this.box = element('input', { type: 'number', step: 'any', 'aria-label': spoken });
      this.slider.addEventListener('input', () => {
        this.commit(this.toScene(fromSlider(this.span, Number(this.slider.value))));
      });
      // A drag keeps the span it started on until the pointer lets go: re-centring the span on each
      // value the drag writes would move the value under a still pointer, and compound on every move.
      this.slider.addEventListener('pointerdown', () => {
        this.held = true;
        const release = () => {
          window.removeEventListener('pointerup', release, true);
          window.removeEventListener('pointercancel', release, true);
          this.held = false;
          this.refresh();
        };
        window.addEventListener('pointerup', release, true);
        window.addEventListener('pointercancel', release, true);
      });
      this.box.addEventListener('change', () => {
        this.commit(this.box.value === '' ? NaN : this.toScene(Number(this.box.value)));
      });
      this.unit = element('span', { class: 'unit' });
      this.row.append(this.slider, this.box, this.unit);
    }
    const id = `control-${path.replace(/\W+/g, '-')}`;
    this.error = element('div', { class: 'error', role: 'alert', id: `${id}-error` });
    this.backButton = element('button', { type: 'button' });
    this.backButton.addEventListener('click', () => this.backToRun());
    this.refusalNote = element('div', { class: 'refusal-note', id: `${id}-note`, hidden: '' }, [element('span'), this.backButton]);
    this.row.append(this.error, this.refusalNote);
    this.inputs = [this.check, this.menu, this.slider, this.box].filter(Boolean);
    for (const input of this.inputs) input.setAttribute('aria-describedby', `${this.error.id} ${this.refusalNote.id}`);
    this.row.addEventListener('keydown', (event) => {
      if (event.key === 'Escape' && this.refusal) this.backToRun();
    });
  }

  // The value this control shows: the refused scene's while a refusal is shown, else the scene's.
  value(scene = this.shownScene()) {
    const v = getPath(scene, this.path);
    return v !== undefined ? v : this.key.default;
  }

  shownScene() {
    return this.refusal ? this.refusal.scene : this.page.scene;
  }

  // The units this control shows its number in: the page's, but SI for the keys that fix the seed's.
  units() {
    return kUnitKeys.has(this.path) ? new Units('si') : this.page.units(this.shownScene());
  }

  // A number as this control shows it, with its unit.
  shownWithUnit(value) {
    const units = this.units(), unit = this.key.unit;
    const label = units.label(unit);
    return `${shownNumber(units.shown(value, unit), units.scale(unit) !== 1)}${label ? ` ${label}` : ''}`;
  }

  // A number typed or slid in the units shown, in the scene's SI.
  toScene(value) {
    return this.units().toSI(value, this.key.unit);
  }

  // A change of this control was refused: the control keeps the refused value, marked invalid with
  // the message, and says that the motion on screen is still the last run's, with its value and a
  // way back to it. `refusedScene` is the scene that was refused (the page then edits the last run's).
  refuse(message, refusedScene) {
    this.refusal = { scene: refusedScene };
    this.error.textContent = message;
    const running = this.effect ? hasEffect(this.page.scene, this.effect) : this.value(this.page.scene);
    const shown = running === undefined ? undefined : typeof running === 'boolean' ? (running ? 'on' : 'off')
      : typeof running === 'number' ? this.shownWithUnit(running) : String(running);
    this.refusalNote.firstChild.textContent = `Not run: the motion on screen is still the last run's, ${
      shown === undefined ? `without ${this.path}` : `with ${this.path} = ${shown}`}. `;
    this.backButton.textContent = shown === undefined ? 'Back to the last run' : `Back to ${shown}`;
    this.refresh();
  }

  clearRefusal(replaceTyped = false) {
    this.error.textContent = '';
    if (!this.refusal) return;
    this.refusal = null;
    this.refresh(replaceTyped);
  }

  // Escape or the button: the control shows the last run's value again, and the scene box its scene.
  backToRun() {
    this.clearRefusal(true);
    this.page.showRunning();
  }

  // The scene's value into the control, and whether it applies to this scene; into a box being typed
  // in only when `replaceTyped`.
  refresh(replaceTyped = false) {
    const scene = this.shownScene();
    this.row.classList.toggle('refused', Boolean(this.refusal));
    this.refusalNote.hidden = !this.refusal;
    for (const input of this.inputs) {
      if (this.refusal) input.setAttribute('aria-invalid', 'true');
      else input.removeAttribute('aria-invalid');
    }
    const units = this.units();
    this.row.title = tooltip(this.key, units);
    const present = this.effect ? hasEffect(scene, this.effect) : getPath(scene, this.path) !== undefined;
    let shown = presenceHolds(scene, this.key);
    if (this.path === 'initial[steady].steady' || this.effect) shown = true;
    else if (this.path.startsWith('initial.')) shown = shown && getPath(scene, 'initial[steady].steady') === undefined;
    this.row.hidden = !shown || !this.chosen;
    if (this.check) this.check.checked = this.key.type === 'boolean' ? this.value() === true : present;
    if (this.menu) this.menu.value = this.path === 'initial[steady].steady' ? (this.value() || '(rates)') : this.value();
    if (this.slider) {
      const value = this.value(), unit = this.key.unit, scale = units.scale(unit);
      const shownValue = value !== undefined ? units.shown(value, unit) : NaN;
      const usable = value !== undefined && !(this.optional && !present);
      this.slider.disabled = this.box.disabled = !usable;
      if (replaceTyped || document.activeElement !== this.box) {
        this.box.value = value !== undefined ? shownNumber(shownValue, scale !== 1) : '';
      }
      if (this.key.minimum) this.box.min = this.key.minimum.value / scale;
      if (this.key.maximum) this.box.max = this.key.maximum.value / scale;
      this.unit.textContent = units.label(unit);
      // The slider's span is in the units shown, so that its three digits are the seed's where shown.
      if (!this.held) {
        this.span = sliderScale(this.key, shownValue, scale);
        if (Number.isFinite(shownValue)) this.slider.value = toSlider(this.span, shownValue);
      }
      this.slider.dataset.from = this.span.from;
      this.slider.dataset.to = this.span.to;
    }
  }

  commit(value) {
    if (this.key.type === 'number' && !Number.isFinite(value)) {
      const typed = JSON.parse(JSON.stringify(this.page.scene));
      setPath(typed, this.path, value);
      const units = this.units(), label = units.label(this.key.unit);
      const range = rangeText(this.key, units);
      this.refuse(`${this.path}: type a number${label ? ` in ${label}` : ''}, range ${range}`, typed);
      return;
    }
    setPath(this.page.scene, this.path, value);
    this.page.changed(this.path);
  }

  onCheck() {
    const scene = this.page.scene, on = this.check.checked;
    if (this.effect) setEffect(scene, this.effect, on);
    else if (this.key.type === 'boolean') setPath(scene, this.path, on);
    else if (on) setPath(scene, this.path, this.page.suggestedValue(this.path));
    else deletePath(scene, this.path);
    this.page.changed(this.path);
  }

  onStart() {
    this.page.scene.initial = startFrom(this.page.scene.initial, this.menu.value);
    this.page.changed(this.path);
  }
}

// From rates to a steady motion and back: the tilt and the rolling rate carry over where the new
// start takes them (docs/scene.md initial[steady]); `kind` '(rates)' is an explicit start. The start
// menu and the steady-motion panel's buttons both start this way, so the panel's numbers are those
// of the motion its button starts.
export function startFrom(old = {}, kind, branch) {
  const theta = old.theta !== undefined ? old.theta : 20, omegaZ = old.omega_Z !== undefined ? old.omega_Z : 10;
  const initial = kind === '(rates)' ? { theta, omega_Z: omegaZ } : { steady: kind };
  if (kind === 'circle' || kind === 'spin-in-place') initial.theta = theta;
  if (kind === 'circle' || kind === 'straight') initial.omega_Z = omegaZ;
  if (kind === 'circle' && branch !== undefined) initial.branch = branch;
  return initial;
}

export class Controls {
  // `page`: {scene, changed(path), suggestedValue(path), showRunning()}. `chosen`: the paths a student
  // sees (`coinroll export --controls`), or null for all; the others keep the scene's values, and a
  // group none of whose controls is chosen is left out.
  constructor(container, page, chosen = null) {
    this.controls = [];
    this.groups = [];
    for (const [title, paths] of kGroups) {
      const group = { controls: paths.map((path) => new Control(path, page)) };
      for (const c of group.controls) c.chosen = !chosen || chosen.includes(c.path);
      group.hint = element('p', { class: 'hint', text: whatShows(group.controls[0].key) });
      const fieldset = element('fieldset', {}, [element('legend', { text: title }), group.hint, ...group.controls.map((c) => c.row)]);
      fieldset.hidden = !group.controls.some((c) => c.chosen);
      container.append(fieldset);
      this.controls.push(...group.controls);
      this.groups.push(group);
    }
  }

  refresh() {
    for (const c of this.controls) c.refresh();
    // A group none of whose keys applies (Flight, before sliding is on) says what brings its first one.
    for (const group of this.groups) group.hint.hidden = group.controls.some((c) => !c.row.hidden);
  }

  clearErrors() {
    for (const c of this.controls) c.clearRefusal();
  }

  // Shows at the control of `path`, the one changed, that `refusedScene` was refused with `message`;
  // false where no such control is shown.
  refuse(path, message, refusedScene) {
    const control = this.controls.find((c) => c.path === path);
    if (!control || control.row.hidden) return false;
    control.refuse(message, refusedScene);
    return true;
  }
}

// What a group whose keys all hide says: what the first key's presence rules ask of the page's
// controls, and what those keys' own rules ask first (flight needs sliding, which needs friction).
function whatShows(key) {
  const needs = [];
  const ask = (k) => {
    for (const condition of [...(k.only_with || []), ...(k.needs || [])]) {
      const path = condition.paths[0], other = schemaKey(path);
      ask(other);
      const type = other.type;
      needs.push(type === 'name' ? `${path} is ${condition.values.join(' or ')}` : `${path} is ticked`);
    }
  };
  ask(key);
  return needs.length ? `Shown once ${needs.join(' and ')}.` : '';
}

// Keeps the scene a control changed one the loader takes: a key whose presence rules no longer hold
// leaves it (the loader refuses it: "restitution: only with flight: true"), which can end another's
// (sliding off ends flight's, and flight's restitution's); and a key the schema requires there comes in.
// `running` is the scene on screen, whose coin's moments a coin made custom starts with.
export function fitScene(scene, running) {
  const paths = kGroups.flatMap(([, group]) => group).filter((path) => !/^(effects|initial)\[/.test(path));
  for (let removed = true; removed;) {
    removed = false;
    for (const path of paths) {
      if (getPath(scene, path) === undefined || presenceHolds(scene, schemaKey(path))) continue;
      deletePath(scene, path);
      removed = true;
    }
  }
  for (const path of paths) {
    const key = schemaKey(path);
    if (!key.required || !key.only_with || getPath(scene, path) !== undefined || !presenceHolds(scene, key)) continue;
    setPath(scene, path, path.startsWith('coin.I_') ? momentsOf(running.coin)[path.slice(5)] : suggestedValue(path));
  }
}

// A thin coin's moments, kg m^2, by coin.shape's doc in the loader's arithmetic (physics/coin_model.cpp),
// so that a disk made custom runs bit for bit as it did. A coin with thickness has a solid's moments
// (docs/rim_inertia.md), which the page does not compute: its custom copy moves a little differently.
function momentsOf(coin) {
  if (coin.shape === 'custom') return { I_X: coin.I_X, I_Z: coin.I_Z };
  if (coin.shape !== 'ring') return { I_X: coin.mass * coin.radius * coin.radius / 4, I_Z: coin.mass * coin.radius * coin.radius / 2 };
  const b = coin.inner_radius !== undefined ? coin.inner_radius : coin.radius;
  const sumOfSquares = coin.radius * coin.radius + b * b;
  return { I_X: coin.mass * sumOfSquares / 4, I_Z: coin.mass * sumOfSquares / 2 };
}

// What a ticked optional key starts at: its schema default, else the schema's example of it
// (`friction` 0.5, `coin.thickness` 0.003), else 1 of its unit.
export function suggestedValue(path) {
  const example = schemaKey(path).example;
  return defaultOf(path, example !== undefined ? example : 1);
}
