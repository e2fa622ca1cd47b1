// The stream and string-decoder stand-ins drive the Gerber libraries as the real packages do.
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
