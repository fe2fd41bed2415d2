// One run of the core as the page reads it: the CSV's columns (every number from the WebAssembly
// module) and the coin's state between rows, and the run's visual track from the same core
// (src/pipeline/visual_track.h): the camera `coinroll render` draws with and the overlay's lines as it
// prints them, per row, and the clip's clock, each frame's time and playback rate.
//
// The rates are the CSV's own rates in other components, not physics: in the seed's frame
// omega = theta-dot e_X + phi-dot e_y + psi-dot e_Z with e_y = cos(theta) e_Y - sin(theta) e_Z
// (docs/seed.md §2), so omega_X = theta-dot, omega_Y = phi-dot cos(theta) and
// omega_Z = psi-dot - phi-dot sin(theta); between rows they carry the angles round smoothly.

const kFrameTolerance = 1e-9;  // s, as render's windows allow (pipeline/video_frames.h kWindowTolerance)

// Columns that hold their row's value between rows rather than being interpolated: flags and counts.
const kHeldColumns = ['t', 'sliding', 'phase', 'impacts'];

export function rates(theta, omegaX, omegaY, omegaZ) {
  const phiDot = omegaY / Math.cos(theta);
  return { thetaDot: omegaX, phiDot, psiDot: omegaZ + phiDot * Math.sin(theta) };
}

// Cubic Hermite between two rows of an angle and its rate, so that a heading that turns a radian
// between rows still turns smoothly on screen.
function hermite(p0, p1, d0, d1, h, f) {
  const f2 = f * f, f3 = f2 * f;
  const value = (2 * f3 - 3 * f2 + 1) * p0 + (f3 - 2 * f2 + f) * h * d0 + (-2 * f3 + 3 * f2) * p1 + (f3 - f2) * h * d1;
  return Number.isFinite(value) ? value : p0 + (p1 - p0) * f;
}

export class Trajectory {
  // result: what the worker sends back (core.visualRun's names, columns, rows, sampleDt, end, events,
  // report and visual track); scene: the scene object that was run.
  constructor(result, scene) {
    Object.assign(this, { names: result.names, columns: result.columns, rows: result.rows, sampleDt: result.sampleDt,
                          end: result.end, events: result.events, report: result.report, visual: result.visual, scene });
    this.endTime = this.columns.t[this.rows - 1];
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

  // The overlay at simulated time t, the core's lines at the nearest row: in SI as `coinroll render`
  // prints them, or in the seed's units (`seed`).
  overlayAt(t, seed) {
    const { i, f } = this.locate(t);
    return this.visual.overlay[seed ? 'seed' : 'si'][f > 0.5 ? i + 1 : i];
  }

  // Simulated seconds per second of playback at t: the clip's, as `coinroll render` plays it (the
  // core's clock: render.time_scale, slowed by render.time_remap where the coin turns fast, flies or
  // strikes the floor), that of the last frame at or before t. A frame within kFrameTolerance of t
  // counts as at t: a time the program printed is the page's to round-off only, since the frame times
  // are sums of steps that depend on the motion, which the WebAssembly computes to libm's last bits.
  playbackRate(t) {
    const { times, playbackRates, simulatedFrames } = this.visual.clock;
    let low = 0, high = simulatedFrames - 1;
    while (low < high) {
      const middle = (low + high + 1) >> 1;
      if (times[middle] <= t + kFrameTolerance) low = middle;
      else high = middle - 1;
    }
    return playbackRates[low];
  }

  // The scene's camera at t, as `coinroll render` places it for its picture (render.camera, framed to
  // render.width x render.height): the core's at each row, linear between rows. {eye, target, up, fov}.
  cameraAt(t) {
    const { i, f } = this.locate(t), { eye, target, up, fov } = this.visual.cameras;
    const j = f > 0 ? i + 1 : i;
    const mix = (array, k) => array[3 * i + k] + (array[3 * j + k] - array[3 * i + k]) * f;
    const triple = (array) => [mix(array, 0), mix(array, 1), mix(array, 2)];
    return { eye: triple(eye), target: triple(target), up: Array.from(up.subarray(3 * i, 3 * i + 3)),
             fov: fov[i] + (fov[j] - fov[i]) * f };
  }
}
