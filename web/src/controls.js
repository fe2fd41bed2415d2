// The page's controls, each built from its key in the scene schema (`coinroll schema`): the label is
// the key, the tooltip its doc, range and default, the unit its unit; a number gets a slider (on a
// log scale where its range spans decades) and a box for the exact value, a name a menu, a boolean
// a checkbox; a key without a default that may be absent (thickness, friction) gets a checkbox that
// puts it in the scene or takes it out. A control is shown only where its only_with assignments hold.
import schema, { defaultOf, deletePath, getPath, hasEffect, onlyWithHolds, schemaKey, setEffect, setPath } from './schema.js';

// What the page offers, in its groups; every range, default, unit and text comes from the schema.
export const kGroups = [
  ['Coin', ['coin.shape', 'coin.radius', 'coin.inner_radius', 'coin.thickness', 'coin.edge_radius', 'coin.mass']],
  ['Start', ['initial[steady].steady', 'initial.theta', 'initial.phi', 'initial.omega_X', 'initial.omega_Y', 'initial.omega_Z',
             'initial.x', 'initial.z', 'initial[steady].theta', 'initial[steady].omega_Z', 'initial[steady].branch']],
  ['Floor contact', ['friction', 'friction_static', 'sliding', 'initial.v_x', 'initial.v_z']],
  ['Effects', ['effects[air_drag]', 'effects[air_drag].model', 'effects[air_drag].viscosity', 'effects[air_drag].density',
               'effects[rolling_resistance]', 'effects[rolling_resistance].length', 'effects[spin_friction]', 'effects[spin_friction].length']],
  ['Run', ['duration', 'gravity']],
];

const kSliderSteps = 1000;

function rangeText(key) {
  const lo = key.minimum, hi = key.maximum;
  if (lo && hi) return `${lo.inclusive ? '[' : '('}${lo.value}, ${hi.value}${hi.inclusive ? ']' : ')'}`;
  if (lo) return `${lo.inclusive ? '≥' : '>'} ${lo.value}`;
  if (hi) return `${hi.inclusive ? '≤' : '<'} ${hi.value}`;
  return 'any';
}

function tooltip(key) {
  const parts = [`${key.path}: ${key.doc}`, `range ${rangeText(key)}${key.unit ? ` ${key.unit}` : ''}`];
  if (key.default !== undefined) parts.push(`default ${JSON.stringify(key.default)}`);
  else if (key.required) parts.push('required');
  else parts.push('optional: unticked, the key is left out of the scene');
  return parts.join('\n');
}

// The slider's span for a value: the schema's range where it is narrow enough to slide through; a
// log scale where it is positive and spans decades (two decades either side of the value, inside
// the range); else a linear window round the value that grows as the value does.
function sliderScale(key, value) {
  const lo = key.minimum ? key.minimum.value : -Infinity, hi = key.maximum ? key.maximum.value : Infinity;
  const v = Number.isFinite(value) ? value : 0;
  if (lo >= 0 && v > 0 && !(hi / Math.max(lo, Number.MIN_VALUE) < 100)) {
    const from = Math.max(lo > 0 ? lo : v * 1e-2, v * 1e-2), to = Math.min(hi, v * 1e2);
    return { log: true, from, to };
  }
  if (Number.isFinite(lo) && Number.isFinite(hi) && hi - lo <= 1000) return { log: false, from: lo, to: hi };
  const half = Math.pow(10, Math.ceil(Math.log10(Math.max(Math.abs(v), 1e-9) * 4)));
  const span = Math.max(half, lo >= 0 ? 1 : 10);
  return { log: false, from: Math.max(lo, lo >= 0 ? 0 : v - span), to: Math.min(hi, v + span) };
}

const toSlider = (scale, value) => {
  const f = scale.log ? Math.log(value / scale.from) / Math.log(scale.to / scale.from) : (value - scale.from) / (scale.to - scale.from);
  return Math.round(kSliderSteps * Math.min(1, Math.max(0, f)));
};
// Three significant digits off the slider, so that what it writes into the scene reads cleanly.
const fromSlider = (scale, position) => {
  const f = position / kSliderSteps;
  const value = scale.log ? scale.from * Math.pow(scale.to / scale.from, f) : scale.from + f * (scale.to - scale.from);
  return value === 0 ? 0 : Number(value.toPrecision(3));
};

// Small numbers in exponent form, which a narrow box shows whole (1.8e-5, not 0.000018).
const numberText = (value) => (value !== 0 && Math.abs(value) < 1e-3 ? value.toExponential() : String(value));

function element(tag, attributes = {}, children = []) {
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
    this.row = element('div', { class: this.effect || this.key.type === 'boolean' ? 'control whole' : 'control', title: tooltip(this.key), 'data-path': path });
    const label = element('label', { class: 'name', text: this.effect ? this.effect.replace(/_/g, ' ') : path.replace(/^.*\./, '') });
    this.row.append(label);
    if (this.effect || this.optional || this.key.type === 'boolean') {
      this.check = element('input', { type: 'checkbox', 'aria-label': `${path} on` });
      this.check.addEventListener('change', () => this.onCheck());
      label.prepend(this.check);
    }
    if (this.key.path === 'initial[steady].steady') {
      this.menu = element('select', { 'aria-label': path }, ['(rates)', ...this.key.names].map((n) => element('option', { value: n, text: n })));
      this.menu.addEventListener('change', () => this.onStart());
      this.row.append(this.menu);
    } else if (this.key.type === 'name' && !this.effect) {
      this.menu = element('select', { 'aria-label': path }, this.key.names.map((n) => element('option', { value: n, text: n })));
      this.menu.addEventListener('change', () => this.commit(this.menu.value));
      this.row.append(this.menu);
    } else if (this.key.type === 'number') {
      this.slider = element('input', { type: 'range', min: 0, max: kSliderSteps, step: 1, 'aria-label': `${path} slider` });
      this.box = element('input', { type: 'number', step: 'any', 'aria-label': path });
      if (this.key.minimum) this.box.min = this.key.minimum.value;
      if (this.key.maximum) this.box.max = this.key.maximum.value;
      this.slider.addEventListener('input', () => this.commit(fromSlider(this.scale, Number(this.slider.value))));
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
      this.box.addEventListener('change', () => this.commit(this.box.value === '' ? NaN : Number(this.box.value)));
      this.row.append(this.slider, this.box, element('span', { class: 'unit', text: this.key.unit || '' }));
    }
    this.error = element('div', { class: 'error', role: 'alert' });
    this.row.append(this.error);
  }

  value() {
    const v = getPath(this.page.scene, this.path);
    return v !== undefined ? v : this.key.default;
  }

  // The scene's value into the control, and whether it applies to this scene.
  refresh() {
    const scene = this.page.scene;
    const present = this.effect ? hasEffect(scene, this.effect) : getPath(scene, this.path) !== undefined;
    let shown = onlyWithHolds(scene, this.key);
    if (this.path === 'initial[steady].steady' || this.effect) shown = true;
    else if (this.path.startsWith('initial.')) shown = shown && getPath(scene, 'initial[steady].steady') === undefined;
    this.row.hidden = !shown;
    if (this.check) this.check.checked = this.key.type === 'boolean' ? this.value() === true : present;
    if (this.menu) this.menu.value = this.path === 'initial[steady].steady' ? (this.value() || '(rates)') : this.value();
    if (this.slider) {
      const value = this.value();
      const usable = value !== undefined && !(this.optional && !present);
      this.slider.disabled = this.box.disabled = !usable;
      if (document.activeElement !== this.box) this.box.value = value !== undefined ? numberText(value) : '';
      if (!this.held) {
        this.scale = sliderScale(this.key, Number(value));
        if (value !== undefined) this.slider.value = toSlider(this.scale, value);
      }
      this.slider.dataset.from = this.scale.from;
      this.slider.dataset.to = this.scale.to;
    }
  }

  commit(value) {
    if (this.key.type === 'number' && !Number.isFinite(value)) {
      this.error.textContent = `${this.path}: type a number${this.key.unit ? ` in ${this.key.unit}` : ''}, range ${rangeText(this.key)}`;
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

  // From rates to a steady motion and back: the tilt and the rolling rate carry over where the new
  // start takes them (docs/scene.md initial[steady]).
  onStart() {
    const old = this.page.scene.initial || {};
    const kind = this.menu.value;
    const theta = old.theta !== undefined ? old.theta : 20, omegaZ = old.omega_Z !== undefined ? old.omega_Z : 10;
    const initial = kind === '(rates)' ? { theta, omega_Z: omegaZ } : { steady: kind };
    if (kind === 'circle' || kind === 'spin-in-place') initial.theta = theta;
    if (kind === 'circle' || kind === 'straight') initial.omega_Z = omegaZ;
    this.page.scene.initial = initial;
    this.page.changed(this.path);
  }
}

export class Controls {
  // `page`: {scene, changed(path), suggestedValue(path)}.
  constructor(container, page) {
    this.controls = [];
    for (const [title, paths] of kGroups) {
      const group = element('fieldset', {}, [element('legend', { text: title })]);
      for (const path of paths) {
        const control = new Control(path, page);
        this.controls.push(control);
        group.append(control.row);
      }
      container.append(group);
    }
  }

  refresh() {
    for (const c of this.controls) c.refresh();
  }

  clearErrors() {
    for (const c of this.controls) c.error.textContent = '';
  }

  // Shows `message` at the control of `path` (or the nearest enclosing one); false where none is.
  showError(path, message) {
    const candidates = this.controls.filter((c) => !c.row.hidden && (path === c.path || path.startsWith(`${c.path}.`)));
    const control = candidates.sort((a, b) => b.path.length - a.path.length)[0];
    if (!control) return false;
    control.error.textContent = message;
    return true;
  }
}

// What a ticked optional key starts at: its schema default, else the value the schema's own
// examples give it (only_with's `friction=0.5`, `coin.thickness=0.003`), else 1 of its unit.
export function suggestedValue(path) {
  const example = schema.keys.flatMap((k) => k.only_with || []).find((a) => a.startsWith(`${path}=`));
  return defaultOf(path, example !== undefined ? JSON.parse(example.slice(path.length + 1)) : 1);
}
