// The simulated Mega's information, report, link and config commands (protocol/mega.md §5 "Information
// and link", "Config and safety"), and the report lines other families print too.

import { formatReply } from '../protocol/dialect-reply';
import { CONFIG_DEFAULTS, num, validConfig } from './config';
import type { Handler, MegaModel } from './mega';
import type { Xyz } from './motion';

const p = (c: Parameters<Handler>[0]) => ('params' in c ? c.params : {});
const text = (c: Parameters<Handler>[0]) => ('text' in c ? c.text : '');

export function temperatureLine(m: MegaModel): string {
  return formatReply({ kind: 'temps', deciC: m.nano.deciC() });
}

export function positionLine(m: MegaModel): string {
  const pos = m.motion.now();
  const steps = pos.map((v, i) => Math.round((v / 1000) * num(m.config, ['steps_per_mm.x', 'steps_per_mm.y', 'steps_per_mm.z'][i]))) as Xyz;
  return formatReply({ kind: 'position', um: pos, steps });
}

export function jobLine(m: MegaModel): string {
  const j = m.job;
  if (j.state === 'idle' || !j.plan) return formatReply({ kind: 'job', state: j.state, fields: {} });
  const fields: Record<string, string> = {
    file: j.file,
    stop: `${j.done}/${j.plan.count}`,
    elapsed: String(Math.floor(j.elapsedUs() / 1e6)), // running time, as the Mega counts it
    ...(j.planComplete ? { remaining: String(Math.round(j.remainingUs() / 1e6)) } : {}), // unknown mid-stream
    leds: String(m.nano.lit),
  };
  if (j.reason) fields.reason = j.reason;
  if (j.streaming) fields.mode = 'stream';
  if (j.paced) fields.paced = '1';
  if (j.cooling) fields.cooling = '1';
  return formatReply({ kind: 'job', state: j.state, fields });
}

/** M27's answer: a G-code file's bytes as Marlin prints them while one is selected, else the job. */
export function statusLine(m: MegaModel): string {
  return m.cardPrint ? m.cardPrint.statusLine() : jobLine(m);
}

type ReportKind = 'temp' | 'pos' | 'job';
const reports = new WeakMap<MegaModel, Record<ReportKind, object | null>>();

/** M155, M154, M27 S: a report every `periodMs` (0 stops it); null or out of range is E11. */
export function autoReport(m: MegaModel, kind: ReportKind, periodMs: number | null | undefined, done: () => void): void {
  if (typeof periodMs !== 'number' || periodMs < 0 || periodMs > 60000) return m.error(11, done);
  const timers = reports.get(m) ?? { temp: null, pos: null, job: null };
  reports.set(m, timers);
  m.clock.cancel(timers[kind]);
  timers[kind] = null;
  if (periodMs > 0) {
    const tick = () => {
      m.line(kind === 'temp' ? temperatureLine(m) : kind === 'pos' ? positionLine(m) : statusLine(m));
      timers[kind] = m.clock.after(periodMs * 1000, tick);
    };
    timers[kind] = m.clock.after(periodMs * 1000, tick);
  }
  done();
}

export function infoCommands(m: MegaModel): Record<string, Handler> {
  return {
    M115: (_c, done) => {
      m.line(formatReply({ kind: 'firmware', name: m.o.firmwareName, protocol: 1 }));
      const caps = [['RX_WINDOW', 3 /* mega.ts WINDOW: the USB port's */], ['AUTOREPORT_TEMP', 1], ['AUTOREPORT_POS', 1], ['SDCARD', m.sd.present ? 1 : 0], ['RESUME', 1]] as const;
      for (const [k, v] of caps) m.line(`Cap:${k}:${v}`);
      done();
    },
    M105: (_c, done) => {
      if (!m.nano.present) return m.error(30, done);
      m.line(temperatureLine(m));
      done();
    },
    // S is in seconds, parsed as thousandths: thousandths of a second are milliseconds.
    M155: (c, done) => autoReport(m, 'temp', p(c).S, done),
    M154: (c, done) => {
      const ms = p(c).P;
      if (typeof ms === 'number') return autoReport(m, 'pos', ms >= 50000 ? ms / 1000 : -1, done);
      autoReport(m, 'pos', p(c).S, done);
    },
    M114: (_c, done) => {
      m.line(positionLine(m));
      done();
    },
    M117: (c, done) => {
      m.message = text(c).slice(0, 16); // the panel's last row
      done();
    },
    M113: (c, done) => {
      const s = p(c).S;
      if (s === undefined) {
        m.line(`echo:M113 S${m.keepaliveUs / 1e6}`);
        return done();
      }
      if (typeof s !== 'number' || s < 0 || s > 60000 || s % 1000) return m.error(11, done);
      m.keepaliveUs = s * 1000;
      done();
    },
    M821: (_c, done) => {
      // The model runs each command in zero virtual time: no loop is ever late, nothing is dropped.
      m.line('echo:DIAG loop_max_us=0 step_isr_max_us=0 underruns=0 rx_dropped=0 tx_dropped=0');
      done();
    },
    M850: (c, done) => {
      const [key, value] = text(c).split(/\s+/);
      if (!(key in CONFIG_DEFAULTS)) return m.error(50, done, key);
      if (value === undefined) {
        m.line(`M850 ${key} ${m.config[key]}`);
        return done();
      }
      if (!validConfig(key, value)) return m.error(50, done, `${key} ${value}`);
      m.config[key] = value;
      done();
    },
    M500: (_c, done) => {
      if (m.job.state === 'running') return m.error(12, done);
      m.eeprom = { ...m.config };
      if (!m.sd.present) {
        m.line('echo:Settings stored in EEPROM only: no SD card');
        return done();
      }
      m.sd.files.set('CONFIG.TXT', Object.entries(m.config).map(([k, v]) => `${k} = ${v}\n`).join(''));
      m.line('echo:Settings stored');
      done();
    },
    M501: (_c, done) => {
      if (m.job.state === 'running') return m.error(12, done);
      m.loadConfig();
      done();
    },
    M502: (_c, done) => (Object.assign(m.config, CONFIG_DEFAULTS), done()),
    M503: (_c, done) => {
      for (const [k, v] of Object.entries(m.config)) m.line(`M850 ${k} ${v}`);
      done();
    },
    M112: (_c, done) => done(), // already acted on at arrival
    M999: (_c, done) => ((m.halted = false), done()),
    M110: (_c, done) => m.error(11, done),
  };
}
