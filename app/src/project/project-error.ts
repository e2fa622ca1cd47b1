// Why a project cannot be opened, and the largest file read: what the session needs before the
// project file format (project-file.ts) has loaded.

/** Larger files are refused before they are read. */
export const MAX_PROJECT_BYTES = 200 * 1024 * 1024;

export class ProjectError extends Error {}
