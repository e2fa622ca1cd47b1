// The dialect's stable numeric error codes (protocol/errors.csv); never renumber.

export const ERRORS = {
  invalid_byte: { code: 1, message: 'invalid byte in line' },
  checksum_mismatch: { code: 2, message: 'checksum mismatch' },
  no_checksum: { code: 3, message: 'line number without checksum' },
  no_line_number: { code: 4, message: 'checksum without line number' },
  line_too_long: { code: 5, message: 'line too long' },
  line_sequence: { code: 6, message: 'line number is not last line number+1' },
  unknown_command: { code: 10, message: 'unknown command' },
  bad_parameter: { code: 11, message: 'bad or missing parameter' },
  busy: { code: 12, message: 'not allowed while a job is running' },
  halted: { code: 13, message: 'machine halted: send M999' },
  not_homed: { code: 14, message: 'axis not homed' },
  soft_limit: { code: 15, message: 'target outside soft limits' },
  no_sd: { code: 20, message: 'no SD card' },
  file_not_found: { code: 21, message: 'file not found' },
  file_error: { code: 22, message: 'SD read or write error' },
  job_malformed: { code: 23, message: 'job record malformed' },
  job_hash_mismatch: { code: 24, message: 'job hash mismatch' },
  job_incomplete: { code: 25, message: 'job upload incomplete' },
  no_job: { code: 26, message: 'no job selected' },
  no_resume: { code: 27, message: 'no interrupted job to resume' },
  stream_overflow: { code: 28, message: 'stream buffer too small for this job' },
  scan_unsupported: { code: 29, message: 'scan job not supported by this machine' },
  nano_timeout: { code: 30, message: 'printhead not responding' },
  over_temperature: { code: 31, message: 'over-temperature' },
  sensor_fault: { code: 32, message: 'temperature sensor fault' },
  exposure_refused: { code: 33, message: 'printhead refused an exposure' },
  link_speed: { code: 34, message: "printhead link not at the job's planned speed" },
  probe_alarm: { code: 40, message: 'probe alarm' },
  probe_no_trigger: { code: 41, message: 'probe did not trigger' },
  endstop_hit: { code: 42, message: 'unexpected endstop hit' },
  selftest_failed: { code: 43, message: 'self-test failed' },
  homing_failed: { code: 44, message: 'endstop not found while homing' },
  config_invalid: { code: 50, message: 'config value invalid' },
} as const;

export type ErrorName = keyof typeof ERRORS;

/** Codes 1-6 are line-level: a numbered line with one of them is asked for again. */
export function isLineError(code: number): boolean {
  return code >= 1 && code <= 6;
}

/** The class of each code (errors.csv): a link error, a refusal that leaves the machine fine, or a fault. */
export type ErrorClass = 'link' | 'refusal' | 'fault';

const FAULTS = new Set([13, 28, 30, 31, 32, 33, 34, 40, 41, 42, 43, 44]);

/** Faults mean the machine stopped or is in danger; refusals are answered `echo:E<code>` as Marlin answers them (mega.md §2). */
export function errorClass(code: number): ErrorClass {
  return isLineError(code) ? 'link' : FAULTS.has(code) ? 'fault' : 'refusal';
}

/** The line that reports an error: `Error:E<code> …` for link errors and faults, `echo:E<code> …` for refusals. */
export function formatError(code: number, detail?: string): string {
  const message = `E${code} ${errorByCode(code)?.message ?? 'error'}${detail ? `: ${detail}` : ''}`;
  return errorClass(code) === 'refusal' ? `echo:${message}` : `Error:${message}`;
}

export function errorByCode(code: number): { name: ErrorName; message: string } | undefined {
  for (const [name, e] of Object.entries(ERRORS)) {
    if (e.code === code) return { name: name as ErrorName, message: e.message };
  }
  return undefined;
}
