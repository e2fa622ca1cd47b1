// A duration in µs as h:mm:ss, the way the preview and the exposure question show estimates.

export function hms(us: number): string {
  const s = Math.round(us / 1e6);
  return `${Math.floor(s / 3600)}:${String(Math.floor((s % 3600) / 60)).padStart(2, '0')}:${String(s % 60).padStart(2, '0')}`;
}
