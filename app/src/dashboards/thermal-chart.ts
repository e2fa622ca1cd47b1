// The thermal chart: uPlot, loaded with the thermal dashboard rather than with the app, drawing the six
// sensors' history and each distinct soft limit as a dashed line in the colour of its sensors.

import uPlot from 'uplot';
import uPlotCss from 'uplot/dist/uPlot.min.css?inline';
import { agoLabel, secondsAgo, timeAxis, type TimeAxis } from './chart-time';
import { SENSOR_COLOURS } from './sensor-colours';
import { warmCanvasFonts, whenIdle } from '../ui/later';

export interface ThermalChart {
  /** `data[0]` is the printer's time in seconds; the chart shows it as time before the newest sample. */
  update(data: [number[], ...number[][]], limitsC: number[] | null): void;
  resize(width: number): void;
  destroy(): void;
}

/** uPlot's styles come with this chunk, not in the first load's stylesheet: added once, when the first chart is made. */
function addStyles(): void {
  if (document.getElementById('uplot-styles')) return;
  const style = Object.assign(document.createElement('style'), { id: 'uplot-styles', textContent: uPlotCss });
  document.head.append(style);
}

/** The axes' fonts, uPlot's own defaults, named here so that `warmText` draws with them. */
const AXIS_FONT = '12px system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, "Noto Sans", sans-serif, "Apple Color Emoji", "Segoe UI Emoji", "Segoe UI Symbol", "Noto Color Emoji"';
const LABEL_FONT = `bold ${AXIS_FONT}`;

/**
 * Readies the page for the first chart, in an idle task of its own before it is made: uPlot's styles
 * added, and the axes' fonts drawn once (ui/later.ts). Made in one go, the chart was the page
 * load's longest task (issue 40).
 */
export function warmText(): void {
  addStyles();
  warmCanvasFonts([AXIS_FONT, LABEL_FONT], '-20 min 0123456789 s °C now time before');
}

/** The readings under the cursor: how long before now, and each sensor's value (null where none). */
export interface ThermalCursor {
  ago: string;
  celsius: (number | null)[];
}

/**
 * The chart has no legend of its own: the dashboard's table of sensors is the one legend (colours,
 * names, limits), and shows the readings under the cursor through `onCursor` (null: the cursor left).
 */
export function thermalChart(el: HTMLElement, names: string[], width: number, onCursor: (at: ThermalCursor | null) => void = () => {}): ThermalChart {
  addStyles();
  let limits: number[] | null = null;
  // The time axis is set here, not left to uPlot: its own ticks on a few seconds of samples read
  // "-2 s, -2 s, -1 s" and, on none, "20 min … 100 min" (issue 29, item 12).
  let axis: TimeAxis = timeAxis(0);
  const caption = 'time before now';
  el.dataset.timeCaption = caption; // the canvas draws it: for a test to read
  const cursorMoved = (u: uPlot) => {
    const idx = u.cursor.idx;
    const at = idx == null ? undefined : (u.data[0][idx] as number | undefined);
    if (idx == null || at === undefined) return onCursor(null);
    onCursor({ ago: agoLabel(at), celsius: names.map((_, i) => { const v = u.data[i + 1][idx]; return v == null || Number.isNaN(v) ? null : v; }) });
  };
  // Made in two tasks (issue 40): uPlot's options, series and axes now; its element placed and its
  // first drawing when the page is next idle (at most 500 ms later), through uPlot's own `then`. In
  // one task the two were 40–50 ms, the page load's longest. Data and a width that come between wait.
  let drawn = false;
  let waiting: uPlot.AlignedData | null = null;
  let waitingWidth: number | null = null;
  let unscheduled = () => {};
  const plot = new uPlot(
    {
      width,
      height: 220,
      scales: {
        x: { time: false, range: () => [-axis.spanS, 0] },
        y: { range: (_u, lo, hi) => [Math.floor(Math.min(lo, 20)), Math.ceil(Math.max(hi, ...(limits ?? [])) + 2)] },
      },
      series: [
        { label: 'Time' },
        ...names.map((label, i) => ({ label, stroke: SENSOR_COLOURS[i], width: 1.5 })),
      ],
      axes: [
        {
          label: caption,
          font: AXIS_FONT,
          labelFont: LABEL_FONT,
          splits: () => axis.ticks,
          values: (_u, ticks) => {
            const words = ticks.map(agoLabel);
            el.dataset.timeTicks = words.join(', '); // what the canvas shows, for a test to read
            return words;
          },
        },
        { label: '°C', size: 44, font: AXIS_FONT, labelFont: LABEL_FONT },
      ],
      legend: { show: false },
      hooks: {
        setCursor: [cursorMoved],
        draw: [
          (u) => {
            if (!limits) return;
            const ctx = u.ctx;
            ctx.save();
            ctx.setLineDash([6, 4]);
            ctx.lineWidth = 1.5;
            const seen = new Set<number>();
            limits.forEach((c, i) => {
              if (seen.has(c)) return;
              seen.add(c);
              const y = u.valToPos(c, 'y', true);
              ctx.strokeStyle = SENSOR_COLOURS[i];
              ctx.beginPath();
              ctx.moveTo(u.bbox.left, y);
              ctx.lineTo(u.bbox.left + u.bbox.width, y);
              ctx.stroke();
            });
            ctx.restore();
          },
        ],
      },
    },
    [[], ...names.map(() => [])],
    (u, init) => {
      unscheduled = whenIdle(() => {
        el.append(u.root);
        init();
        drawn = true;
        if (waitingWidth !== null) u.setSize({ width: waitingWidth, height: 220 });
        if (waiting) show(waiting);
      }, 500);
    },
  );
  const show = (data: uPlot.AlignedData) => {
    plot.setData(data);
    cursorMoved(plot); // new samples move what lies under a cursor held still
  };
  return {
    update(data, limitsC) {
      limits = limitsC;
      const [times, ...sensors] = data;
      axis = timeAxis(times.length ? times[times.length - 1] - times[0] : 0);
      const shown: uPlot.AlignedData = [secondsAgo(times), ...sensors];
      if (drawn) show(shown);
      else waiting = shown;
    },
    resize: (w) => (drawn ? plot.setSize({ width: w, height: 220 }) : (waitingWidth = w)),
    destroy: () => (unscheduled(), plot.destroy()),
  };
}
