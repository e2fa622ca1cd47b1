import { describe, expect, it } from 'vitest';
import { ConsoleLog, DEFAULT_LEVELS, filterLog, KEPT, levelOf, type Level } from './console-log';

describe('console log', () => {
  it('sorts lines by level', () => {
    expect(levelOf('Error:E31 over-temperature')).toBe('error');
    expect(levelOf('echo:E14 axis not homed: X')).toBe('error'); // a refusal: the command was not carried out
    expect(levelOf('echo:Done saving file.')).toBe('info');
    expect(levelOf('FAULT:E31 over-temperature T3 71.2')).toBe('error');
    expect(levelOf('Resend: 5')).toBe('warning');
    expect(levelOf('T:31.2 /0.0 S0:24.0 /0.0')).toBe('report');
    expect(levelOf('JOB:running file=A.UVJ stop=1/9')).toBe('report');
    expect(levelOf('ok N4 P8 B3*1a2b')).toBe('link');
    expect(levelOf('FIRMWARE_NAME:UVExposure 0.1.0 (Mega) PROTOCOL_VERSION:1')).toBe('info');
  });

  it('keeps a bounded log and filters it by level and text, newest last', () => {
    const log = new ConsoleLog({ info: 5 });
    for (let i = 0; i < 8; i++) log.add(`echo:line ${i}`);
    log.trim();
    expect(log.entries.map((e) => e.text)).toEqual(['echo:line 3', 'echo:line 4', 'echo:line 5', 'echo:line 6', 'echo:line 7']);
    log.add('T:25.0 /55.0');
    log.add('Error:E10 unknown command: M9999');
    const shown = filterLog(log.entries, { text: '', levels: new Set(DEFAULT_LEVELS) });
    expect(shown.map((e) => e.level)).not.toContain('report');
    expect(shown.at(-1)!.text).toBe('Error:E10 unknown command: M9999');
    expect(filterLog(log.entries, { text: 'LINE 6', levels: new Set(DEFAULT_LEVELS) }).map((e) => e.text)).toEqual(['echo:line 6']);
  });
});

describe('replies to what the user typed', () => {
  it('shows a reply block\'s reports as replies, leaves errors and other auto-reports alone', () => {
    const log = new ConsoleLog();
    const auto = log.add('T:23.0 /55.0 T0:23.0 /55.0');
    const reply = log.add('X:1.000 Y:2.000 Z:3.000 E:0.000 Count X:80 Y:160 Z:1200');
    const err = log.add('Error:E10 unknown command');
    log.markReplies([reply, err]);
    expect(reply.level).toBe('reply');
    expect(err.level).toBe('error');
    expect(auto.level).toBe('report');
    const shown = filterLog(log.entries, { text: '', levels: new Set(DEFAULT_LEVELS) });
    expect(shown.map((e) => e.text)).toEqual([reply.text, err.text]);
  });
});

describe('what stays in a long job (issue 29, item 11)', () => {
  /** An hour of a job at one report of each kind a second, and an ok for each, with a few lines of the user's among them. */
  function hourOfJob(log: ConsoleLog) {
    log.add('M105', 'sent');
    const reply = log.add('T:23.0 /55.0 T0:23.0 /55.0');
    log.markReplies([reply]);
    log.add('FAULT:E31 over-temperature T3 56.2');
    for (let s = 0; s < 3600; s++) {
      log.add(`T:${(30 + s / 1000).toFixed(1)} /55.0`);
      log.add(`JOB:running file=A.UVJ stop=${s}/3600`);
      log.add('X:1.000 Y:2.000 Z:3.000 E:0.000 Count X:80 Y:160 Z:1200');
      log.add(`ok N${s}`);
      if (s === 1800) log.add('M25', 'sent');
    }
  }

  it('keeps what the user typed, its replies and every fault, however many auto-reports come after them', () => {
    const log = new ConsoleLog();
    hourOfJob(log);
    const shown = filterLog(log.entries, { text: '', levels: new Set(DEFAULT_LEVELS) });
    expect(shown.map((e) => e.text)).toEqual(['M105', 'T:23.0 /55.0 T0:23.0 /55.0', 'FAULT:E31 over-temperature T3 56.2', 'M25']);
  });

  it('bounds each level on its own, newest kept, and the whole log with them', () => {
    const log = new ConsoleLog();
    hourOfJob(log);
    const count = (l: Level) => log.entries.filter((e) => e.level === l).length;
    expect(count('report')).toBeGreaterThanOrEqual(KEPT.report);
    expect(count('report')).toBeLessThanOrEqual(KEPT.report * 1.25);
    expect(count('link')).toBeLessThanOrEqual(KEPT.link * 1.25);
    expect(log.entries.at(-1)!.text).toBe('ok N3599');
    expect(log.added).toBe(3 + 3600 * 4 + 1);
    // Order is kept: times never go back.
    const order = log.entries.map((e) => e.atMs);
    expect(order).toEqual([...order].sort((a, b) => a - b));
  });

  it('drops the oldest of a level only past its own bound', () => {
    const log = new ConsoleLog({ error: 3, report: 2 });
    for (let i = 0; i < 5; i++) log.add(`Error:E1 n${i}`);
    for (let i = 0; i < 9; i++) log.add(`T:2${i}.0 /55.0`);
    log.trim();
    expect(log.entries.map((e) => e.text)).toEqual(['Error:E1 n2', 'Error:E1 n3', 'Error:E1 n4', 'T:27.0 /55.0', 'T:28.0 /55.0']);
  });
});
