// What the app takes from the Mega <-> Nano printhead link (protocol/nano.md); the app never talks to
// the Nano, and the link's codec is the firmware's C++ (firmware/common/protocol/src/nano_codec.*).

/** The printhead's temperature sensors: the Mega's temperature report carries one pair each. */
export const SENSOR_COUNT = 6;
/** The events a scan program holds (nano.md "Scan programs"): the Mega cuts a pass's chain into programs of this many. */
export const PROGRAM_EVENTS = 64;
/** The speeds an `L` may ask for: 115200 and the three exact at 16 MHz with U2X. Any other is refused. */
export const NANO_LINK_BAUDS: readonly number[] = [115200, 250000, 500000, 1000000];

/** Formats tenths of a degree as the link's one-decimal Celsius. */
export function formatDeciC(v: number): string {
  const a = Math.abs(v);
  return `${v < 0 ? '-' : ''}${Math.floor(a / 10)}.${a % 10}`;
}

/** Parses `-?d{1,3}.d` into tenths; null if not that shape. */
export function parseDeciC(s: string, maxIntDigits = 3): number | null {
  const m = /^(-?)([0-9]+)\.([0-9])$/.exec(s);
  if (!m || m[2].length > maxIntDigits) return null;
  const v = Number(m[2]) * 10 + Number(m[3]);
  return m[1] ? -v : v;
}
