// The stream and string-decoder stand-ins drive the Gerber libraries as the real packages do.
import { createRequire } from 'node:module';
import { describe, expect, it } from 'vitest';
import { StringDecoder } from './string-decoder-shim';
import { Transform } from './stream-shim';

interface Emitter {
  on(event: string, l: (...a: unknown[]) => void): Emitter;
  emit(event: string, ...a: unknown[]): boolean;
  push(c: unknown): boolean;
}

describe('the readable-stream stand-in', () => {
  function Lib(this: Emitter) {
    (Transform as unknown as (this: Emitter, o: object) => void).call(this, { readableObjectMode: true });
  }
  Lib.prototype = Object.create(Transform.prototype);

  it('is constructed as the libraries construct it and tells warnings to every listener', () => {
    const lib = new (Lib as unknown as new () => Emitter)();
    const heard: unknown[] = [];
    lib.on('warning', (w) => heard.push(w)).on('warning', (w) => heard.push(['again', w]));
    expect(lib.emit('warning', { line: 3, message: 'm' })).toBe(true);
    expect(heard).toEqual([{ line: 3, message: 'm' }, ['again', { line: 3, message: 'm' }]]);
    expect(lib.emit('other')).toBe(false);
  });

  it('refuses to be read: its driver must catch what it pushes', () => {
    const lib = new (Lib as unknown as new () => Emitter)();
    expect(() => lib.push({})).toThrow(/replace its push/);
  });
});

describe('the string_decoder stand-in', () => {
  it('keeps a character split across chunks whole', () => {
    const d = new StringDecoder('utf8');
    const bytes = new TextEncoder().encode('µm');
    expect(d.write(bytes.subarray(0, 1)) + d.write(bytes.subarray(1)) + d.end()).toBe('µm');
    expect(d.write('G04*')).toBe('G04*');
  });
});

// The lodash helpers the Gerber libraries require, and the language's own that stand in for them in the
// browser build (app/vite.config.ts): the same answers where the libraries call them, and around it.
describe('the lodash stand-ins', () => {
  const require = createRequire(import.meta.url);
  const cases: Record<string, unknown[][]> = {
    padstart: [['123', 6, '0'], ['1234567', 4, '0'], ['', 3, '0'], ['-12', 5, '0'], ['7', 3], [12, 4, '0']],
    padend: [['123', 6, '0'], ['1234567', 4, '0'], ['', 3, '0'], ['7', 3], [12, 4, '0']],
    fill: [[Array(3), false], [[1, 2, 3, 4], 0, 1, 3], [[], true]],
    isfunction: [[() => 0], [function named() {}], [{}], [null], ['f']],
    isfinite: [[3], [-0.5], [Infinity], [NaN], ['3'], [null], [undefined]],
  };
  // Each call gets arrays of its own: fill changes the array it is given.
  const fresh = (args: unknown[]) => args.map((a) => (Array.isArray(a) ? [...a] : a));
  it.each(Object.keys(cases))('%s answers as lodash does', (name) => {
    const lodash = require(`lodash.${name}`) as (...a: unknown[]) => unknown;
    const shim = require(`./lodash-shims/${name}.cjs`) as (...a: unknown[]) => unknown;
    for (const args of cases[name]) expect(shim(...fresh(args)), `${name}(${args.map(String).join(', ')})`).toEqual(lodash(...fresh(args)));
  });
});
