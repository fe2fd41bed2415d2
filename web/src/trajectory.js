// One run of the core as the page reads it: the CSV's columns (every number from the WebAssembly
// module), the coin's state between rows, the overlay's lines as the renderer prints them
// (src/pipeline/snapshot.cpp hudLines) and the playback rate of render.time_scale and
// render.time_remap (src/pipeline/video_frames.cpp playbackRate; its flight and impact slow-downs,
// src/pipeline/slow_motion.cpp).
//
// The overlay's rates are the CSV's own rates in other components, not physics: in the seed's frame
// omega = theta-dot e_X + phi-dot e_y + psi-dot e_Z with e_y = cos(theta) e_Y - sin(theta) e_Z
// (docs/seed.md §2), so omega_X = theta-dot, omega_Y = phi-dot cos(theta) and
// omega_Z = psi-dot - phi-dot sin(theta).
import { formatG } from './units.js';

const kTurn = 2 * Math.PI;

// Simulated seconds between the renderer's trace points and survey samples
// (src/pipeline/motion_survey.cpp traceInterval): the page samples its runs at this step, so that its
// trace and its automatic camera are the program's.
export const traceInterval = (duration) => Math.max(1 / 240, duration / 20000);

// Columns that hold their row's value between rows rather than being interpolated: flags and counts.
const kHeldColumns = ['t', 'sliding', 'phase', 'impacts'];

export function rates(theta, omegaX, omegaY, omegaZ) {
  const phiDot = omegaY / Math.cos(theta);
  return { thetaDot: omegaX, phiDot, psiDot: omegaZ + phiDot * Math.sin(theta),
           // physics::axisGoesRound: the axis circles the vertical (|phi-dot cos(theta)|) at least as
           // fast as it nods (|theta-dot|); an exactly flat axis has no heading.
           axisGoesRound: Math.abs(Math.cos(theta)) >= 1e-12 && Math.abs(omegaY) >= Math.abs(omegaX) };
}

// Cubic Hermite between two rows of an angle and its rate, so that a heading that turns a radian
// between rows still turns smoothly on screen.
function hermite(p0, p1, d0, d1, h, f) {
  const f2 = f * f, f3 = f2 * f;
  const value = (2 * f3 - 3 * f2 + 1) * p0 + (f3 - 2 * f2 + f) * h * d0 + (-2 * f3 + 3 * f2) * p1 + (f3 - f2) * h * d1;
  return Number.isFinite(value) ? value : p0 + (p1 - p0) * f;
}

const fixed = (value, digits, width) => value.toFixed(digits).padStart(width);
// Zero where the digits shown would print -0.00.
const shownTo = (value, digits) => (Math.abs(value) < 0.5 * Math.pow(10, -digits) ? 0 : value);

export class Trajectory {
  // result: what the worker sends back (core.simulate's names, columns, rows, end, events, report);
  // scene: the scene object that was run; sampleDt: the step it was sampled at, s; render: the
  // scene's time_scale, fps and time_remap with the schema's defaults filled in.
  constructor(result, scene, sampleDt, render) {
    Object.assign(this, { names: result.names, columns: result.columns, rows: result.rows, end: result.end,
                          events: result.events, report: result.report, scene, sampleDt, render });
    this.endTime = this.columns.t[this.rows - 1];
    this.hasEffects = Array.isArray(scene.effects) && scene.effects.length > 0;
    this.impacts = Array.from(result.impacts || []);
    this.flights = this.stretchesInTheAir();
  }

  // The stretches in the air that render.time_remap.flight follows, as src/pipeline/slow_motion.cpp
  // scheduleOf reads them off the renderer's grid (the rows j sampleDt apart while the run lasts): each
  // from the last row on the floor before it (or 0) to the last impact in the step where the coin is
  // down again (or the run's end).
  stretchesInTheAir() {
    const { phase } = this.columns, dt = this.sampleDt, flights = [];
    if (!phase) return flights;
    const flies = [];
    for (let j = 0; j < this.rows && j * dt <= this.endTime; ++j) flies.push(phase[j] === 2);
    for (let j = 0; j < flies.length;) {
      if (!flies[j]) { ++j; continue; }
      const first = j;
      while (j < flies.length && flies[j]) ++j;
      const span = { start: first === 0 ? 0 : (first - 1) * dt, end: this.endTime };
      if (j < flies.length) {
        span.end = j * dt;
        const within = this.impacts.filter((t) => t > (j - 1) * dt && t <= j * dt);
        if (within.length > 0) span.end = within[within.length - 1];
      }
      flights.push(span);
    }
    return flights;
  }

  // The row at or before t and the fraction of the step past it; a time on a row is that row.
  locate(t) {
    const x = Math.min(Math.max(t, 0), this.endTime) / this.sampleDt;
    const nearest = Math.round(x);
    if (Math.abs(x - nearest) < 1e-9) return { i: Math.min(nearest, this.rows - 1), f: 0 };
    const i = Math.min(Math.floor(x), this.rows - 2);
    return { i, f: x - i };
  }

  row(i) {
    const state = {};
    for (const name of this.names) state[name] = this.columns[name][i];
    return state;
  }

  // Every column at t (the CSV's own numbers on a row), with the rates and the overlay's lines.
  stateAt(t) {
    const { i, f } = this.locate(t);
    const state = this.row(i);
    if (f > 0) {
      const next = this.row(i + 1);
      const a = rates(state.theta, state.omega_X, state.omega_Y, state.omega_Z);
      const b = rates(next.theta, next.omega_X, next.omega_Y, next.omega_Z);
      const h = this.sampleDt;
      for (const name of this.names) {
        if (!kHeldColumns.includes(name)) state[name] += (next[name] - state[name]) * f;
      }
      state.theta = hermite(this.columns.theta[i], next.theta, a.thetaDot, b.thetaDot, h, f);
      state.phi = hermite(this.columns.phi[i], next.phi, a.phiDot, b.phiDot, h, f);
      state.psi = hermite(this.columns.psi[i], next.psi, a.psiDot, b.psiDot, h, f);
      state.t = this.columns.t[i] + f * h;
    }
    Object.assign(state, rates(state.theta, state.omega_X, state.omega_Y, state.omega_Z));
    return state;
  }

  // The overlay: in SI the renderer's, word for word and in its number formats; in the seed's units
  // (units.js) its rates are the seed's |φ̇| and ω_Z in √(g/a), radians per unit of time, not turns
  // per second.
  hudLines(s, units) {
    const degrees = 180 / Math.PI, rate = units.label('rad/s');
    const [contact, face] = units.seed
      ? [`${fixed(units.shown(Math.abs(s.phiDot), 'rad/s'), 3, 9)} ${rate} round the floor`,
         `${fixed(shownTo(units.shown(s.omega_Z, 'rad/s'), 3), 3, 9)} ${rate} about its axis`]
      : [`${fixed(Math.abs(s.phiDot) / kTurn, 2, 9)} Hz round the floor`,
         `${fixed(shownTo(s.omega_Z / kTurn, 2), 2, 9)} Hz about its axis`];
    const tilt = `${fixed(shownTo(s.theta * degrees, 2), 2, 9)}° from vertical, ` +
                 `${(90 - Math.abs(s.theta) * degrees).toFixed(2)}° above the floor`;
    const lines = [
      `t        ${fixed(units.shown(s.t, 's'), 3, 9)} ${units.label('s')}`,
      `θ        ${tilt}`,
      s.phase === 2 ? 'contact         -- in the air'
        : s.axisGoesRound ? `contact  ${contact}` : 'contact         -- rocking, not going round',
      `face     ${face}`,
      `E        ${fixed(units.shown(s.energy, 'J'), 5, 9)} ${units.label('J')}`,
    ];
    // The seed's power and slip are small numbers: four digits, not a fixed point.
    const small = (value, unit) => `${formatG(units.shown(value, unit), 4).padStart(9)} ${units.label(unit)}`;
    if (this.hasEffects) {
      lines.push(`P        ${units.seed ? small(s.power, 'W') : `${fixed(1e3 * s.power, 3, 9)} mW`} dissipated`);
    }
    if (s.sliding === 1) {
      const slip = units.seed ? small(s.slip_speed, 'm/s') : `${fixed(1e3 * s.slip_speed, 2, 9)} mm/s`;
      lines.push(`sliding  ${slip} slip`);
    }
    if (s.phase === 2 || s.impacts > 0) {
      lines.push(`${(s.phase === 2 ? 'flight' : 'landed').padEnd(8)} ${String(s.impacts).padStart(9)} impact${s.impacts === 1 ? '' : 's'}`);
    }
    return lines;
  }

  // Simulated seconds per second of playback at a moment of the run: render.time_scale, slowed where
  // render.time_remap's rate (|psi-dot| or |phi-dot|) exceeds its limit S, to
  // v = max(time_scale S, min(time_scale S (rate / S)^growth, pi fps / 2)) rad per second on screen.
  // Slower still, with render.time_remap.flight or .impact, in the air and around each impact: the
  // slowest of the rules plays.
  playbackRate(state) {
    const { time_scale: timeScale, time_remap: remap } = this.render;
    if (!remap) return timeScale;
    let rate = timeScale;
    if (remap.spin_rate !== undefined || remap.precession_rate !== undefined) rate = this.byRate(state, remap);
    if (remap.flight || remap.impact) rate = Math.min(rate, timeScale * this.slowDownAt(state.t, remap));
    return rate;
  }

  byRate(state, remap) {
    const { time_scale: timeScale, fps } = this.render;
    const bySpin = remap.spin_rate !== undefined;
    const limit = bySpin ? remap.spin_rate : remap.precession_rate;
    const rate = Math.abs(bySpin ? state.psiDot : state.phiDot);
    if (!(rate > limit)) return timeScale;
    const held = timeScale * limit;
    const quarterTurnPerFrame = Math.PI / 2 * fps;
    const visible = Math.max(held, Math.min(held * Math.pow(rate / limit, remap.growth), quarterTurnPerFrame));
    return Math.min(timeScale, visible / rate);
  }

  // time_scale's multiplier at simulated time t: slow + (1 - slow) e(d / window), e(x) = 3x^2 - 2x^3, d the
  // distance to the nearest stretch in the air (0 inside) or impact, the slower of the two
  // (src/pipeline/slow_motion.h easedMultiplier).
  slowDownAt(t, remap) {
    const eased = ({ slow, window }, distance) => {
      if (distance <= 0) return slow;
      if (distance >= window) return 1;
      const x = distance / window;
      return slow + (1 - slow) * x * x * (3 - 2 * x);
    };
    let multiplier = 1;
    if (remap.flight) {
      const distance = Math.min(...this.flights.map(({ start, end }) => Math.max(start - t, t - end, 0)));
      multiplier = Math.min(multiplier, eased(remap.flight, distance));
    }
    if (remap.impact) {
      const distance = Math.min(...this.impacts.map((time) => Math.abs(time - t)));
      multiplier = Math.min(multiplier, eased(remap.impact, distance));
    }
    return multiplier;
  }

  // The box round every centre and contact point (the renderer's survey).
  survey() {
    const { x, y, z, contact_x: cx, contact_z: cz } = this.columns;
    const lower = [Infinity, Infinity, Infinity], upper = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < this.rows; ++i) {
      for (const p of [[x[i], y[i], z[i]], [cx[i], 0, cz[i]]]) {
        for (let c = 0; c < 3; ++c) { lower[c] = Math.min(lower[c], p[c]); upper[c] = Math.max(upper[c], p[c]); }
      }
    }
    return { lower, upper };
  }
}
