// Stands in for the npm 'readable-stream' package in the browser build (an alias in app/vite.config.ts).
//
// Why: gerber-parser and gerber-plotter are Node transform streams, but tracespace.ts never streams
// through them: it calls the parser's `_process`/`_flush` and the plotter's `_transform`/`_flush`
// directly and catches what they push. All the libraries need of a stream is to construct one
// (`Transform.call(this, options)` then `inherits(…, Transform)`), to `push` (the plotter's, which
// tracespace.ts replaces) and to `emit('warning')` to listeners added with `on`. The real package
// brings Node's streams, Buffer, process and events polyfills: about half the Gerber chunk.

type Listener = (...args: unknown[]) => void;

interface ShimTransform {
  _listeners: Map<string, Listener[]>;
  on(event: string, listener: Listener): ShimTransform;
  emit(event: string, ...args: unknown[]): boolean;
  push(chunk: unknown): boolean;
}

/** A constructor in the ES5 style, as the libraries call it: `Transform.call(this, options)`. */
export function Transform(this: ShimTransform): void {
  this._listeners = new Map();
}

Transform.prototype.on = function (this: ShimTransform, event: string, listener: Listener): ShimTransform {
  this._listeners.set(event, [...(this._listeners.get(event) ?? []), listener]);
  return this;
};

Transform.prototype.emit = function (this: ShimTransform, event: string, ...args: unknown[]): boolean {
  const listeners = this._listeners.get(event) ?? [];
  for (const l of listeners) l(...args);
  return listeners.length > 0;
};

/** Nothing reads this stream: whoever drives it catches what it pushes by replacing `push`. */
Transform.prototype.push = function (): boolean {
  throw new Error('this stream stands in for readable-stream and cannot be read: replace its push');
};

export default { Transform };
