// Follows the printer's job and tells its end where a person away from the screen sees it: the
// page's title (as long as the job's line shows the end) and a desktop notification, if allowed.

import type { Printer } from '../device/connection.svelte';
import type { JobProgress } from '../device/device-state';
import { jobEnd, pageTitle } from './job-notice';

export class JobNotice {
  /** The last end not yet seen by the user, e.g. "Job done"; null once the page was looked at. */
  unseen = $state<string | null>(null);
  #last: JobProgress | null = null;

  constructor(private readonly printer: Printer) {}

  /** Asks once, from a click that starts a job, whether the desktop may be told when it ends. */
  static askPermission(): void {
    if (typeof Notification !== 'undefined' && Notification.permission === 'default') void Notification.requestPermission().catch(() => {});
  }

  /** Called on every change of the job (an effect in the app). */
  follow(): void {
    const job = this.printer.device.job;
    const end = jobEnd(this.#last, job);
    this.#last = job ? { ...job } : null;
    if (end) {
      this.unseen = document.hasFocus() && document.visibilityState === 'visible' ? null : end.title;
      if (typeof Notification !== 'undefined' && Notification.permission === 'granted') new Notification(end.title, { body: end.body, tag: 'uv-job' });
    }
    const title = pageTitle(job, this.unseen);
    if (document.title !== title) document.title = title; // reports arrive many times a second
  }

  /** The user is back at the page: the end has been seen. */
  seen = (): void => {
    if (document.visibilityState !== 'visible' || !this.unseen) return;
    this.unseen = null;
    document.title = pageTitle(this.printer.device.job, null);
  };
}
