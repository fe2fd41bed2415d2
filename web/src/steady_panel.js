// The seed's steady motions beside the motion (docs/web.md "Steady motions"): for the coin and the
// tilt of the run on screen, each steady motion `coinroll steady` reports (straight, circle on
// either root, spin in place), with its linear stability, and a button that starts it. The numbers
// are the WebAssembly core's (core.steady in the worker, with the run), shown with the digits the
// command prints them with, so that a student can hold the page against `coinroll steady`, in SI or
// in the seed's units.
import { element, startFrom, symbol } from './controls.js';
import { formatG, Units } from './units.js';

// The panel's motions: the kind and circle root, as `coinroll steady --kind K --branch B` takes them.
export const kSteadyMotions = [
  { kind: 'straight', title: 'Straight rolling', about: 'upright, rolling along a line' },
  { kind: 'circle', branch: '+', title: 'Circle, root f+', about: 'tilted, rolling round a circle; ω_Y the root f+ of the seed\'s quadratic (docs/seed.md §5)' },
  { kind: 'circle', branch: '-', title: 'Circle, root f−', about: 'tilted, rolling round a circle; ω_Y the root f− of the seed\'s quadratic (docs/seed.md §5)' },
  { kind: 'spin-in-place', title: 'Spin in place', about: 'centre of mass at rest, the coin rolling round on its rim' },
];

// `coinroll steady`'s requests for the scene's start: each motion from the scene's tilt and spin, as
// its button would start it.
export function steadyRequests(initial) {
  return kSteadyMotions.map(({ kind, branch }) => {
    const start = startFrom(initial, kind, branch);
    const request = { kind };
    if (start.theta !== undefined) request.theta = start.theta;
    if (start.omega_Z !== undefined) request.omega_Z = start.omega_Z;
    if (branch !== undefined) request.branch = branch;
    return request;
  });
}

const kSI = new Units('si');

// The tilt's amplitude a nudge gives a stable motion, in degrees: small enough for the linear
// wobble's period to hold to a tenth of a per cent, large enough to see.
const kNudgeDegrees = 1;

// The times of the tilt's maxima on a run's rows (t, theta), each refined by the parabola through the
// row and its two neighbours.
function tiltMaxima(t, theta, rows) {
  const maxima = [];
  for (let i = 1; i + 1 < rows; ++i) {
    if (!(theta[i] > theta[i - 1] && theta[i] >= theta[i + 1])) continue;
    const curvature = theta[i - 1] - 2 * theta[i] + theta[i + 1];
    const offset = curvature < 0 ? 0.5 * (theta[i - 1] - theta[i + 1]) / curvature : 0;
    maxima.push(t[i] + offset * (t[i + 1] - t[i]));
  }
  return maxima;
}

// One number, given in the SI `unit` and shown in `units`: `quantity` names it for the test
// (tests/web/page_test.mjs), `digits` the command's format for it ('6g', '9g', '12g', '6f'), kept in
// the seed's units too.
function number(quantity, value, digits, unit, units = kSI) {
  const label = units.label(unit);
  return element('span', { class: 'value' }, [bareNumber(quantity, value, digits, unit, units),
                                               label ? ` ${label}` : '']);
}

// The number alone, for a unit that follows other text (±λ i 1/s).
function bareNumber(quantity, value, digits, unit, units = kSI) {
  const precision = Number(digits.slice(0, -1)), shown = units.shown(value, unit);
  const text = digits.endsWith('f') ? shown.toFixed(precision) : formatG(shown, precision);
  return element('span', { class: 'number', 'data-quantity': quantity, 'data-unit': units.label(unit), text });
}

// A labelled number: the symbol, its tooltip saying what it is, the value with its unit; `wide`
// takes the rest of the row.
function entry(name, about, value, wide = false) {
  const attributes = Object.assign({ title: about }, wide ? { class: 'wide' } : {});
  return [element('dt', attributes, symbol(name)), element('dd', attributes, [value])];
}

export class SteadyPanel {
  // `start(initial)`: runs the scene on screen with this start.
  constructor(container, start) {
    this.start = start;
    this.intro = element('p', { class: 'hint' });
    this.coin = element('p', { class: 'steady-coin' });
    this.cards = kSteadyMotions.map((motion, i) => {
      const button = element('button', { type: 'button', text: 'Start' });
      button.addEventListener('click', () => this.start(startFrom(this.initial, motion.kind, motion.branch)));
      const nudge = element('button', { type: 'button', class: 'nudge', text: `Nudge ${kNudgeDegrees}°` });
      nudge.addEventListener('click', () => this.nudge(i));
      const card = element('div', { class: 'steady-motion', 'data-kind': motion.kind, 'data-branch': motion.branch || '' }, [
        element('div', { class: 'steady-head' }, [element('strong', { text: motion.title, title: motion.about }),
                                                  element('span', { class: 'verdict' }), button, nudge]),
        // Not an .error: nothing the student typed is refused, this coin has no such motion here.
        element('dl'), element('div', { class: 'steady-refusal' }),
      ]);
      return { motion, card, button, nudge };
    });
    this.wobble = element('p', { class: 'wobble', hidden: true });
    container.append(element('legend', { text: 'Steady motions' }), this.intro, this.coin, this.wobble,
                     ...this.cards.map((c) => c.card));
  }

  // Starts motion `i` tapped: its tilt rate omega_X = sqrt|K| times kNudgeDegrees, all else as in the
  // motion. Since the rates' perturbations follow the tilt's (docs/derivations.md eqs. 3.3-3.4), a kick
  // in the tilt rate alone leaves the motion's two other constants as they were, so the run wobbles
  // about this motion itself, kNudgeDegrees each way, and its period differs from 2 pi / sqrt K only
  // at second order (0.09 % at 1 degree, 0.023 % at half a degree on the steady circle). A nudge of
  // the tilt with the rates kept would move it to a neighbouring motion instead (-9 % there).
  nudge(i) {
    const { report } = this.results[i];
    const { theta, omega_Y: omegaY, omega_Z: omegaZ } = report.initial;
    const tiltRate = Math.sqrt(Math.abs(report.stiffness)) * kNudgeDegrees * Math.PI / 180;
    const initial = { theta, omega_X: tiltRate, omega_Y: omegaY, omega_Z: omegaZ };
    this.nudged = { initial, title: kSteadyMotions[i].title, stability: report.stability };
    this.start(initial);
  }

  // For a run started by nudge(): the tilt's wobble measured on the run (the mean spacing of the
  // tilt's maxima, each placed by the parabola through its row and their neighbours), beside the
  // predicted period 2 pi / sqrt(K); for an unstable motion, its e-folding time to watch for.
  showWobble(trajectory, units) {
    Object.assign(this, { trajectory, units });
    const nudged = this.nudged;
    const mine = nudged && JSON.stringify(trajectory.scene.initial) === JSON.stringify(nudged.initial);
    this.wobble.hidden = !mine;
    if (!mine) return;
    const { stability } = nudged;
    this.wobble.className = `wobble ${stability.verdict}`;
    const predicted = number('predictedPeriod', stability.time, '9g', 's', units);
    const lead = `${nudged.title}, nudged (tilt rate ω_X = √|K| × ${kNudgeDegrees}°): `;
    if (stability.verdict !== 'stable') {
      this.wobble.replaceChildren(lead, `${stability.verdict}: the tilt leaves the motion`,
        ...(stability.verdict === 'unstable' ? [', growing like exp(t/τ), τ = ', number('predictedTime', stability.time, '6g', 's', units)] : []),
        '. Watch the tilt plot.');
      return;
    }
    const maxima = tiltMaxima(trajectory.columns.t, trajectory.columns.theta, trajectory.rows);
    if (maxima.length < 2) {
      this.wobble.replaceChildren(lead, 'the run is shorter than one wobble; predicted period 2π/√K = ', predicted, '.');
      return;
    }
    const measured = (maxima[maxima.length - 1] - maxima[0]) / (maxima.length - 1);
    const difference = (measured / stability.time - 1) * 100;
    this.wobble.replaceChildren(lead, 'the tilt wobbles with period ', number('measuredPeriod', measured, '6g', 's', units),
      ` measured over ${maxima.length - 1} wobbles of the run, against 2π/√K = `, predicted,
      ` predicted (${difference >= 0 ? '+' : ''}${difference.toFixed(2)} %, a second-order effect of the ${kNudgeDegrees}° wobble).`);
  }

  // The same motions in other units.
  setUnits(units) {
    if (this.results) this.show(this.initial, this.results, units);
    if (this.trajectory) this.showWobble(this.trajectory, units);
  }

  // The steady motions of the run on screen: `initial` its scene's start, `results` the core's answer
  // to steadyRequests(initial), in order, each {report} or {error}; `units` those of the numbers shown.
  show(initial, results, units) {
    Object.assign(this, { initial, results });
    const requests = steadyRequests(initial);
    const { theta, omega_Z: omegaZ } = requests[1];
    const spin = units.seed ? `${formatG(units.shown(omegaZ, 'rad/s'), 6)} ${units.label('rad/s')}` : `${omegaZ} rad/s`;
    this.intro.replaceChildren(...symbol(`The seed's steady motions of this coin at the run's tilt θ = ${theta}° ` +
      `and spin ω_Z = ${spin}, as coinroll steady reports them. A small tilt perturbation obeys δθ″ = −K δθ: ` +
      'eigenvalues λ = ±√−K, a wobble where K > 0. Start one to watch it.'));
    const shared = results.find((r) => r.report);
    this.coin.replaceChildren();
    if (shared) {
      // M, a and g are the seed's units, and √(g/a) its unit of rate: they show in SI in either system.
      const { coin, naturalRate, criticalSpin, criticalSpinInNaturalUnits, rim } = shared.report;
      this.coin.append('Coin: M = ', number('M', coin.M, '6g', 'kg'), ', a = ', number('a', coin.a, '6g', 'm'),
                       ', g = ', number('g', coin.g, '6g', 'm/s^2'), units.seed ? ' (the units: each is 1 here)' : '',
                       ', I', element('sub', { text: 'X' }), ' = ', number('I_X', coin.I_X, '6g', 'kg m^2', units),
                       ', I', element('sub', { text: 'Z' }), ' = ', number('I_Z', coin.I_Z, '6g', 'kg m^2', units),
                       '; natural rate √(g/a) = ', number('naturalRate', naturalRate, '6g', 'rad/s'),
                       units.seed ? ' (the unit of rates). ' : '. ');
      if (criticalSpin === null) {
        this.coin.append('No critical spin: a rim with corners switches corners at upright, so it has no straight rolling.');
      } else {
        // In SI the core's own ω_c / √(g/a) follows; in the seed's units, where ω_c shows as that, the SI value.
        const other = units.seed ? number('criticalSpinSI', criticalSpin, '6g', 'rad/s')
          : number('criticalSpinInNaturalUnits', criticalSpinInNaturalUnits, '6f', '√(g/a)');
        this.coin.append(element('span', { title: 'the spin below which straight (upright) rolling is unstable' }, [
          'Critical spin of the upright coin ω', element('sub', { text: 'c' }), ' = ',
          number('criticalSpin', criticalSpin, '6g', 'rad/s', units), ' (', other,
          rim ? '' : '; 1/√3 for the thin disk', ').']));
      }
    }
    this.cards.forEach(({ card, button }, i) => {
      const { report, error } = results[i];
      const verdict = card.querySelector('.verdict');
      const list = card.querySelector('dl');
      card.dataset.request = JSON.stringify(requests[i]);
      card.querySelector('.steady-refusal').textContent = error ? `No such motion here: ${error.message}` : '';
      button.disabled = Boolean(error);
      this.cards[i].nudge.disabled = Boolean(error) || !report || report.stiffness === 0;
      this.cards[i].nudge.title = error ? 'coinroll refuses this start (below)'
        : `runs this motion tapped (tilt rate √|K| × ${kNudgeDegrees}°), to watch the wobble the panel predicts`;
      button.title = error ? 'coinroll refuses this start (below)' : `runs this steady motion: initial ${JSON.stringify(startFrom(initial, requests[i].kind, requests[i].branch))}`;
      list.replaceChildren();
      verdict.className = 'verdict';
      verdict.textContent = '';
      if (!report) return;
      const { stability } = report;
      verdict.classList.add(stability.verdict);
      verdict.textContent = stability.verdict.toUpperCase();
      const shown = (quantity, value, digits, unit) => number(quantity, value, digits, unit, units);
      const eigenvalues = stability.verdict === 'marginal' ? element('span', { text: '0 (twice)' })
        : element('span', {}, ['±', bareNumber('rate', stability.rate, '9g', '1/s', units),
                               stability.verdict === 'stable' ? ' i' : '', ` ${units.label('1/s')}`]);
      const time = stability.verdict === 'stable' ? [' · period ', shown('time', stability.time, '9g', 's')]
        : stability.verdict === 'unstable' ? [' · e-folding time ', shown('time', stability.time, '9g', 's')] : [];
      const { initial: start, radii, reaction } = report;
      list.append(
        ...entry('θ', 'tilt from upright', number('theta', start.theta, '12g', '°')),
        ...entry('ω_Z', 'rolling rate: ω_Z = ψ̇ − φ̇ sin θ (seed eq. 11)',
                 shown('omega_Z', start.omega_Z, '12g', 'rad/s')),
        ...entry('ω_Y', 'ω_Y = φ̇ cos θ (seed eq. 11)', shown('omega_Y', start.omega_Y, '12g', 'rad/s')),
        ...entry('K', 'stiffness of the tilt: δθ″ = −K δθ', shown('K', report.stiffness, '9g', '1/s^2')),
        ...entry('φ̇', 'precession rate: how fast the heading turns',
                 shown('precessionRate', report.precessionRate, '9g', 'rad/s')),
        ...entry('ψ̇', 'spin rate of the face', shown('spinRate', report.spinRate, '9g', 'rad/s')),
        ...entry('R_G', 'radius of the circle the centre of mass traces',
                 shown('radiusCentreOfMass', radii.centreOfMass, '9g', 'm')),
        ...entry('R_C', 'radius of the circle the contact point traces',
                 shown('radiusContact', radii.contact, '9g', 'm')),
        ...entry('N', 'the floor\'s normal force', shown('N', reaction.N, '6g', 'N')),
        ...entry('F', 'the friction force that holds it', shown('F', reaction.F, '6g', 'N')),
        ...entry('μ ≥', 'the least friction coefficient that holds it, F/N', number('frictionNeeded', report.frictionNeeded, '4g')),
        ...entry('λ', 'the linearised eigenvalues of a small tilt perturbation, ±√−K, and the wobble\'s period 2π/√K or the ' +
                 'growth\'s e-folding time 1/√−K', element('span', {}, [eigenvalues, ...time]), true));
    });
  }
}
