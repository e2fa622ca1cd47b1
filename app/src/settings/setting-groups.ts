// The machine's settings in the groups people look for them in, by the first part of each key.

const GROUPS: [string, string][] = [
  ['bed', 'Bed'],
  ['pitch', 'Bed'],
  ['steps_per_mm', 'Motion'],
  ['speed', 'Motion'],
  ['accel', 'Motion'],
  ['invert', 'Motion'],
  ['settle_ms', 'Motion'],
  ['stop_overhead_us', 'Motion'],
  ['led', 'LEDs'],
  ['thermal', 'Thermal'],
  ['mesh', 'Probe and mesh'],
];

export function settingGroups(keys: string[]): { name: string; keys: string[] }[] {
  const out = new Map<string, string[]>();
  for (const key of keys) {
    const name = GROUPS.find(([prefix]) => key === prefix || key.startsWith(`${prefix}.`))?.[1] ?? 'Other';
    out.set(name, [...(out.get(name) ?? []), key]);
  }
  const order = [...new Set(GROUPS.map(([, n]) => n)), 'Other'];
  return order.filter((n) => out.has(n)).map((name) => ({ name, keys: out.get(name)! }));
}
