// A printer's `E<code>` answer to a command, as the links throw it: apart from the link's code, so
// the app reads it on the first screen while the link itself loads on connect (links.ts).

export class CommandError extends Error {
  constructor(readonly code: number, message: string) {
    super(`E${code} ${message}`);
  }
}
