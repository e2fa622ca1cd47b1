// The simulated Mega's card and job commands (protocol/mega.md §5 "Jobs"): exposure jobs (verified uploads,
// runs, streams, resume) and G-code files (stored uploads, runs line by line), side by side on one card.

import type { Command } from '../protocol/dialect-command';
import { JobVerifier } from '../protocol/job-verify';
import { parseNanoReply } from '../protocol/nano';
import { CardPrint, isGcodeName } from './card-gcode';
import { JobStream } from './job-stream';
import { autoReport, statusLine } from './mega-info';
import type { Handler, MegaModel } from './mega';
import { resumeVerdict } from './resume';

/** An M28 of an exposure job: each record checked as it arrives. */
export interface JobUpload {
  file: string;
  verifier: JobVerifier;
  lines: string[];
}

const params = (c: Command) => ('params' in c ? c.params : {});
const text = (c: Command) => ('text' in c ? c.text : '');

function homedXY(m: MegaModel): boolean {
  return m.motion.homed[0] && m.motion.homed[1];
}

/** M23: selects a job (verified and planned) or a G-code file; returns an error code, or 0. */
function select(m: MegaModel, name: string): { code: number; detail?: string } {
  if (!m.sd.present) return { code: 20 };
  const file = m.sd.find(name);
  if (!file) return { code: 21, detail: name };
  if (m.jobActive()) return { code: 12 };
  const body = m.sd.files.get(file)!;
  m.line(`File opened: ${file} Size: ${body.length}`);
  m.line('File selected');
  if (isGcodeName(file)) {
    m.cardPrint = new CardPrint(file, body);
    m.selected = '';
    return { code: 0 };
  }
  m.cardPrint = null;
  m.selected = file;
  return m.job.load(file) ? { code: 0 } : { code: 24 };
}

/** `P1` runs a job paced, `P0` unpaced (mega.md "Pacing"); without P a start is unpaced and a continue keeps its pacing. */
function pacing(m: MegaModel, c: Command | null, fresh: boolean): boolean {
  const p = c ? params(c).P : undefined;
  if (p === undefined) return fresh ? false : m.job.paced;
  return p === 1000;
}

/** P, when given, is 0 or 1. */
function badPacing(c: Command | null): boolean {
  const p = c ? params(c).P : undefined;
  return p !== undefined && p !== 0 && p !== 1000;
}

/** M24: starts or continues the selected G-code file or job. */
function start(m: MegaModel, done: () => void, c: Command | null = null): void {
  if (badPacing(c)) return m.error(11, done, 'P is 0 or 1');
  if (m.cardPrint) {
    m.cardPrint.running = true; // its lines run once this block has ended (MegaModel.pump)
    return done();
  }
  if (m.job.state === 'paused') {
    if (m.tooHot()) return m.error(31, done, 'printhead still faulted');
    m.job.paced = pacing(m, c, false);
    m.job.resume();
    return done();
  }
  if (!m.selected || !m.job.plan) return m.error(26, done);
  if (m.job.state === 'running') return m.error(12, done);
  if (m.tooHot()) return m.error(31, done, 'printhead faulted');
  if (!homedXY(m)) return m.error(14, done, 'home first (G28)');
  if (m.job.state !== 'ready') m.job.load(m.selected);
  m.job.paced = pacing(m, c, true);
  m.job.start(0);
  done();
}

function beginUpload(m: MegaModel, file: string, done: () => void): void {
  if (!isGcodeName(file) && file.includes('~')) return m.error(11, done, "a job's name has no ~"); // `~` marks the Mega's own files
  if (!m.sd.present) return m.error(20, done);
  if (m.jobActive()) return m.error(12, done);
  if (isGcodeName(file)) m.gcodeUpload = { file, lines: [] };
  else {
    m.upload = { file, verifier: new JobVerifier(), lines: [] };
    m.job.state = 'uploading';
  }
  m.line(`echo:Writing to file: ${file}`);
  done();
}

/** Stores a file under its name, replacing one that differs only in case (FAT names). */
function store(m: MegaModel, file: string, body: string): void {
  const old = m.sd.find(file);
  if (old) m.sd.files.delete(old);
  m.sd.files.set(file, body);
}

function endUpload(m: MegaModel, done: () => void): void {
  if (m.gcodeUpload) {
    const u = m.gcodeUpload;
    m.gcodeUpload = null;
    store(m, u.file, u.lines.map((l) => l + '\n').join('')); // the file appears whole, or not at all
    m.line('echo:Done saving file.');
    return done();
  }
  const u = m.upload;
  if (!u) return m.error(11, done, 'not uploading');
  m.upload = null;
  const err = u.verifier.error ?? u.verifier.finish();
  if (err) {
    m.job.state = 'failed';
    return m.error(err.code, done, err.message); // a partial or unverified upload is never stored
  }
  store(m, u.file, u.lines.map((l) => l + '\n').join(''));
  m.job.state = 'idle';
  m.line('echo:Done saving file.');
  done();
}

function endStream(m: MegaModel, done: () => void): void {
  const err = m.stream!.finish();
  m.stream = null;
  if (err) return m.error(err.code, done, err.message);
  m.line('echo:Stream complete.');
  done();
}

function resume(m: MegaModel, c: Command, done: () => void): void {
  const cp = m.sd.checkpoint;
  if ('S' in params(c)) {
    m.line(cp ? `JOB:interrupted file=${cp.file} stop=${cp.done}/${cp.stops}` : 'JOB:idle');
    return done();
  }
  if ('C' in params(c)) {
    m.sd.checkpoint = null;
    return done();
  }
  if (m.cardPrint?.running) return m.error(12, done);
  if (badPacing(c)) return m.error(11, done, 'P is 0 or 1');
  if (!cp) return m.error(27, done);
  if (!homedXY(m)) return m.error(14, done, 'home first (G28)');
  if (!m.job.load(cp.file)) return m.error(21, done, cp.file);
  m.selected = cp.file;
  m.cardPrint = null;
  const { from, verdict } = resumeVerdict(cp, parseNanoReply(m.nano.command('C\n') ?? ''));
  m.job.paced = pacing(m, c, true);
  m.job.start(from);
  m.line(`echo:resume: stop ${cp.done} ${verdict}`);
  done();
}

export function jobCommands(m: MegaModel): Record<string, Handler> {
  return {
    M20: (_c, done) => {
      if (!m.sd.present) return m.error(20, done);
      m.line('Begin file list');
      for (const [name, size] of m.sd.list()) m.line(`${name} ${size}`);
      m.line('End file list');
      done();
    },
    M21: (_c, done) => (m.line(m.sd.present ? 'echo:SD card ok' : 'echo:SD init fail'), done()),
    M28: (c, done) => beginUpload(m, text(c), done),
    M29: (_c, done) => (m.stream ? endStream(m, done) : endUpload(m, done)),
    M828: (c, done) => {
      if (badPacing(c)) return m.error(11, done, 'P is 0 or 1');
      if (m.jobActive()) return m.error(12, done);
      if (!homedXY(m)) return m.error(14, done, 'home first (G28)');
      if (m.tooHot()) return m.error(31, done, 'printhead faulted');
      m.stream = new JobStream(m.job, m.job.machine(m.motion.now()), (e) => m.errorLine(e.code, `${e.line ? `line ${e.line}: ` : ''}${e.message}`));
      m.line('echo:Streaming: exposed as it arrives, no resume');
      m.job.paced = pacing(m, c, true);
      m.job.beginStream('stream');
      done();
    },
    M23: (c, done) => {
      const r = select(m, text(c));
      return r.code ? m.error(r.code, done, r.detail) : done();
    },
    M32: (c, done) => {
      if (!isGcodeName(text(c))) return m.error(11, done, 'M32 runs G-code files; jobs start with M23 and M24');
      const r = select(m, text(c));
      return r.code ? m.error(r.code, done, r.detail) : start(m, done);
    },
    M24: (c, done) => start(m, done, c),
    M25: (_c, done) => {
      if (m.cardPrint) m.cardPrint.running = false; // after the line that runs now
      else m.job.pause();
      done();
    },
    M26: (c, done) => {
      const s = params(c).S;
      if (!m.cardPrint || typeof s !== 'number' || s < 0 || s % 1000) return m.error(11, done);
      m.cardPrint.seek(s / 1000);
      done();
    },
    M27: (c, done) => {
      if ('S' in params(c)) return autoReport(m, 'job', params(c).S, done);
      m.line(statusLine(m));
      done();
    },
    M524: (_c, done) => {
      if (m.upload) {
        m.upload = null; // an upload in progress is given up: nothing is kept (mega.md M524)
        m.job.state = 'aborted';
      }
      m.gcodeUpload = null;
      m.cardPrint = null;
      m.job.abort();
      m.motion.stop();
      done();
    },
    M30: (c, done) => {
      const file = m.sd.present ? m.sd.find(text(c)) : undefined;
      if (!file) return m.error(m.sd.present ? 21 : 20, done, text(c));
      if (m.cardPrint?.file === file) {
        if (m.cardPrint.running) return m.error(12, done);
        m.cardPrint = null;
      }
      m.sd.files.delete(file);
      if (m.selected === file) m.selected = '';
      done();
    },
    M1000: (c, done) => resume(m, c, done),
  };
}
