// Live plots under the view (docs/web.md "Plots"): the run's own columns against time, as the
// WebAssembly core handed them to the page (the CSV's numbers), in the units shown, with the
// playback time as the cursor. Nothing here computes physics: a plotted value is a column times its
// unit's size, θ in degrees, or |F| over μ_s N of the same row. uPlot draws them (a library, not
// canvas code of ours); its own mouse handling is off, so that the cursor is always the motion's
// time and a press or drag on a plot seeks the motion instead of zooming.
import uPlot from 'uplot';
import { element, symbol } from './controls.js';
import { formatG } from './units.js';

const kPlotHeight = 150;  // px, axes included; the legend goes below
const kDegrees = 180 / Math.PI;

// The plots a run has: each a title, its y axes (the unit of each, in SI) and its series, a series a
// column (or columns) of the run with its axis and colour. Those of absent columns are left out.
function plotsOf(trajectory) {
  const { columns, scene } = trajectory;
  // The rolling cone's coefficient, as physics::CoinModel's `cone`: friction_static, else friction.
  const cone = scene.friction_static !== undefined ? scene.friction_static : scene.friction;
  const energy = [{ key: 'energy', label: 'E', unit: 'J', stroke: '#1c1e22' }];
  if (columns.dissipated) energy.push({ key: 'dissipated', label: 'dissipated', unit: 'J', stroke: '#d35400' });
  if (columns.power) energy.push({ key: 'power', label: 'P', unit: 'W', stroke: '#8e44ad', axis: 1 });
  const contact = [{ key: 'normal_force', label: 'N', unit: 'N', stroke: '#16807a' }];
  if (cone === undefined) {
    contact.push({ key: 'friction_force', label: '|F|', unit: 'N', stroke: '#c0392b' });
  } else {
    // In the air N is 0 and the ratio has no value: a gap, not a spike.
    const N = columns.normal_force;
    const ratio = columns.friction_force.map((F, i) => (N[i] > 0 ? F / (cone * N[i]) : NaN));
    contact.push({ key: 'cone_ratio', label: '|F|/μₛN', unit: '', stroke: '#c0392b', axis: 1, values: ratio },
                 { key: 'cone', label: 'cone', unit: '', stroke: '#7f8c8d', axis: 1, dash: [5, 4],
                   values: new Float64Array(trajectory.rows).fill(1) });
  }
  const tilt = columns.theta.map((v) => v * kDegrees);
  return [
    { id: 'tilt', title: 'Tilt', axes: [{ label: 'θ', unit: '°' }],
      series: [{ key: 'theta', label: 'θ', unit: '°', stroke: '#1f4e9c', values: tilt }] },
    { id: 'spins', title: 'Spins (coin frame)', axes: [{ label: 'ω', unit: 'rad/s' }],
      series: [{ key: 'omega_X', label: 'ω_X', unit: 'rad/s', stroke: '#c0392b' },
               { key: 'omega_Y', label: 'ω_Y', unit: 'rad/s', stroke: '#27864a' },
               { key: 'omega_Z', label: 'ω_Z', unit: 'rad/s', stroke: '#1f4e9c' }] },
    { id: 'energy', title: columns.power ? 'Energy and power' : 'Energy', series: energy,
      axes: [{ label: 'E', unit: 'J' }].concat(columns.power ? [{ label: 'P', unit: 'W' }] : []) },
    cone === undefined
      ? { id: 'contact', title: 'Floor reaction', series: contact, axes: [{ label: 'force', unit: 'N' }] }
      // The ratio from 0, and the cone's edge in view however far inside it the coin rolls.
      : { id: 'contact', title: 'Floor reaction and the friction cone', series: contact,
          axes: [{ label: 'N', unit: 'N' }, { label: '|F|/μₛN', unit: '' }],
          rightRange: (u, min, max) => [0, Math.max(1.1, max)] },
  ];
}

// What makes two runs' charts the same but for their data: the plots, their series and axes, and the
// unit system of the axes' labels.
const shapeOf = (plots, units) => JSON.stringify([units.seed, plots.map(({ id, title, axes, series }) =>
  [id, title, axes, series.map((s) => s.key)])]);

const kFont = '11px system-ui, sans-serif';

export class Plots {
  // `container`: the <details> the plots live in; `seek(t)`: shows the motion at simulated time t, s.
  constructor(container, seek) {
    Object.assign(this, { container, seek, charts: [], trajectory: null, units: null, t: 0 });
    this.grid = element('div', { class: 'plot-grid' });
    container.append(element('summary', { text: 'Plots' }), this.grid);
    // Charts are made only while the section is open: a closed one has no width to draw at.
    container.addEventListener('toggle', () => this.build());
    new ResizeObserver(() => this.fit()).observe(this.grid);
  }

  // The run on screen, in `units`.
  show(trajectory, units) {
    Object.assign(this, { trajectory, units });
    // A run with the plots of the last in the same units (a slider moved) only brings new data, which
    // uPlot redraws in a few ms where making the charts anew takes 10-30.
    if (this.charts.length > 0) {
      const plots = plotsOf(trajectory);
      if (shapeOf(plots, units) === this.shape) {
        this.charts.forEach((chart, k) => {
          chart.plot = plots[k];
          chart.setData(this.data(plots[k]));
        });
        return;
      }
    }
    this.build();
  }

  setUnits(units) {
    this.units = units;
    this.build();
  }

  // Moves every plot's cursor to simulated time t, s.
  setTime(t) {
    this.t = t;
    for (const chart of this.charts) this.place(chart);
  }

  place(chart) {
    chart.setCursor({ left: chart.valToPos(this.units.shown(this.t, 's'), 'x'), top: 0 });
  }

  build() {
    for (const chart of this.charts) chart.destroy();
    this.charts = [];
    this.grid.replaceChildren();
    if (!this.trajectory || !this.container.open) return;
    const plots = plotsOf(this.trajectory);
    this.shape = shapeOf(plots, this.units);
    const boxes = plots.map((plot) => element('div', { class: 'plot', 'data-plot': plot.id }));
    this.grid.append(...boxes);
    // Each chart as wide as its column, as the grid's CSS lays the boxes out.
    const width = Math.max(Math.floor(boxes[0].getBoundingClientRect().width), 160);
    plots.forEach((plot, k) => {
      const chart = new uPlot(this.options(plot, width), this.data(plot), boxes[k]);
      chart.plot = plot;
      // Labels with the seed's subscripts (ω_X as ω with X below), which uPlot would print as text.
      chart.root.querySelectorAll('.u-series .u-label').forEach((label, i) => {
        label.replaceChildren(...symbol(i === 0 ? 't' : plot.series[i - 1].label));
      });
      this.bindSeeking(chart);
      this.charts.push(chart);
    });
  }

  fit() {
    if (this.charts.length === 0) return;
    const width = Math.floor(this.charts[0].root.parentElement.getBoundingClientRect().width);
    if (width <= 0 || width === this.charts[0].width) return;
    for (const chart of this.charts) chart.setSize({ width, height: kPlotHeight });
  }

  // The x column in the units shown, then each series' values over its unit's size.
  data(plot) {
    const { columns } = this.trajectory, units = this.units;
    const scaled = (values, unit) => {
      const scale = units.scale(unit);
      return scale === 1 ? values : values.map((v) => v / scale);
    };
    // uPlot draws a gap at null (the ratio in the air), not at NaN.
    const gapped = (values) => Array.from(values, (v) => (Number.isFinite(v) ? v : null));
    return [scaled(columns.t, 's'), ...plot.series.map((s) => gapped(scaled(s.values || columns[s.key], s.unit)))];
  }

  options(plot, width) {
    const units = this.units;
    const axisLabel = ({ label, unit }) => (unit ? `${label} (${units.label(unit)})` : label);
    const value = (u, v) => (v === null || v === undefined ? '–' : formatG(v, 5));
    const axis = (extra) => Object.assign({ font: kFont, labelFont: kFont, labelSize: 14, size: 46, gap: 2,
                                            grid: { stroke: 'rgba(0,0,0,0.08)', width: 1 }, ticks: { size: 4 } },
                                          extra);
    const axes = [axis({ label: `t (${units.label('s')})`, size: 30 }), axis({ label: axisLabel(plot.axes[0]) })];
    if (plot.axes[1]) {
      axes.push(axis({ label: axisLabel(plot.axes[1]), scale: 'right', side: 1, grid: { show: false } }));
    }
    const none = () => null, place = (chart) => this.place(chart);
    return {
      title: plot.title, width, height: kPlotHeight,
      scales: Object.assign({ x: { time: false, range: (u, min, max) => [min, max] } },
                            plot.rightRange ? { right: { range: plot.rightRange } } : {}),
      axes,
      series: [{ label: 't', value },
               ...plot.series.map((s) => ({ label: s.label, stroke: s.stroke, width: 1.5, dash: s.dash, value,
                                            scale: s.axis ? 'right' : 'y', points: { show: false } }))],
      // The playback time is the cursor: uPlot neither follows the mouse nor zooms on a drag.
      cursor: { y: false, drag: { x: false, y: false, setScale: false }, points: { size: 5 },
                bind: { mousedown: none, mouseup: none, dblclick: none, mousemove: none, mouseleave: none,
                        mouseenter: none } },
      legend: { live: true },
      // uPlot lays a chart out after its constructor returns, and scales it after setSize and setData:
      // the cursor is put on the playback time once it has, since valToPos means nothing before.
      hooks: { ready: [place], setSize: [place], setScale: [(chart, key) => key === 'x' && place(chart)] },
    };
  }

  // A press on a plot, and a drag from it, seeks the motion to the time under the pointer.
  bindSeeking(chart) {
    const over = chart.over;
    const seekTo = (event) => {
      const x = event.clientX - over.getBoundingClientRect().left;
      const t = this.units.toSI(chart.posToVal(x, 'x'), 's');
      this.seek(Math.min(Math.max(t, 0), this.trajectory.endTime));
    };
    over.addEventListener('pointerdown', (event) => {
      over.setPointerCapture(event.pointerId);
      seekTo(event);
    });
    over.addEventListener('pointermove', (event) => { if (over.hasPointerCapture(event.pointerId)) seekTo(event); });
  }

  // For the test hook: each plot's row at its cursor, x and series there (by column), and axis labels.
  atCursor() {
    return Object.fromEntries(this.charts.map((chart) => {
      const idx = chart.cursor.idx, { plot } = chart;
      const at = (k) => (idx === null ? null : chart.data[k][idx]);
      const values = Object.fromEntries(plot.series.map((s, k) => [s.key, at(k + 1)]));
      return [plot.id, { idx, x: at(0), values, axes: chart.axes.map((a) => a.label) }];
    }));
  }
}
