// A link's upload rate, measured on the last upload or, before one, the line's, and the upload's time and bytes in words.

/** 115200 baud, 8N1: what the Mega's ports carry at the most, bytes per second. */
export const LINE_RATE_BPS = 115200 / 10;

/** A link's upload rate in wire bytes per second of the printer's time; `measured`: on the last upload, else the line's. */
export interface LinkRate {
  bytesPerS: number;
  measured: boolean;
  /** What its bytes count: whole lines on the wire (the app's own sender), or job text (what the ESP's hub reports). */
  counts?: 'wire' | 'text';
}

export const LINE_RATE: LinkRate = { bytesPerS: LINE_RATE_BPS, measured: false };

/** The upload's bytes in the unit `rate` counts. */
export const uploadBytes = (size: { wireBytes: number; textBytes: number }, rate: LinkRate): number =>
  rate.counts === 'text' ? size.textBytes : size.wireBytes;

/** The upload's time at `rate`, µs. */
export const uploadUs = (wireBytes: number, rate: LinkRate): number => Math.round((wireBytes / rate.bytesPerS) * 1e6);

/** Bytes in KB or MB, as the question and the progress say them. */
export function bytesText(n: number): string {
  return n >= 1e6 ? `${(n / 1e6).toFixed(2)} MB` : n >= 1e4 ? `${Math.round(n / 1e3)} KB` : n >= 1e3 ? `${(n / 1e3).toFixed(1)} KB` : `${n} bytes`;
}

/** The rate as words: "11.5 KB/s, the line's rate" or "9.8 KB/s, as measured on the last upload". */
export function rateText(rate: LinkRate): string {
  return `${(rate.bytesPerS / 1e3).toFixed(1)} KB/s, ${rate.measured ? 'as measured on the last upload' : "the line's rate (no upload measured yet)"}`;
}

/** Seconds of the printer's time the upload under way still needs at its rate so far, or null before the rate is known. */
export function uploadLeftS(u: { bytesSent: number; bytesTotal: number; wireSent?: number; wireTotal?: number; bytesPerS?: number }): number | null {
  if (!u.bytesPerS) return null;
  const left = u.wireTotal !== undefined && u.wireSent !== undefined ? u.wireTotal - u.wireSent : u.bytesTotal - u.bytesSent;
  return Math.max(0, Math.round(left / u.bytesPerS));
}
