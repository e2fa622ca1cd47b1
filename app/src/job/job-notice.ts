// How the end of a job reaches a person in another room: the page's title, and a desktop
// notification when they allowed it. Pure: what to say for a job's state, and whether it just ended.

import type { JobProgress } from '../device/device-state';

export const APP_TITLE = 'UV Exposure';

const ENDED: Record<string, string> = { done: 'Job done', aborted: 'Job stopped', failed: 'Job failed', interrupted: 'Job interrupted' };

/** The words for a job that has just ended, or null if `next` is no end of the job `prev` was running. */
export function jobEnd(prev: JobProgress | null, next: JobProgress | null): { title: string; body: string } | null {
  if (!prev || !next || (prev.state !== 'running' && prev.state !== 'paused') || !(next.state in ENDED)) return null;
  const where = next.stops ? `stop ${next.stop ?? 0} of ${next.stops}` : '';
  const why = next.reason ? ` (${next.reason})` : '';
  return { title: ENDED[next.state], body: `${next.file ?? 'The job'}: ${next.state}${why}${where ? `, ${where}` : ''}.` };
}

/**
 * The page's title: progress while a job runs; its end as long as the job's line shows it (until the
 * next job), or, with the job gone (the printer disconnected), until the user looks; else the app's name.
 */
export function pageTitle(job: JobProgress | null, ended: string | null): string {
  if (job && job.state in ENDED) return `${ENDED[job.state]} · ${APP_TITLE}`;
  if (ended) return `${ended} · ${APP_TITLE}`;
  if (job?.state === 'running' && job.stops) return `${Math.floor(((job.stop ?? 0) / job.stops) * 100)} % exposing · ${APP_TITLE}`;
  if (job?.state === 'paused') return `Paused · ${APP_TITLE}`;
  return APP_TITLE;
}
