// The project open in the studio: its name, turning the editor and the job settings into a project
// and back, files saved and opened, the autosave (a second after the last edit, and before every
// job) and the recent projects. A project that cannot be opened leaves the open one as it was.

import type { JobControl } from '../job/job-control.svelte';
import { GridEditor } from '../studio/editor.svelte';
import { DoseGrid } from '../studio/grid/grid';
import { isArtwork } from '../studio/objects/objects';
import { MAX_PROJECT_BYTES, ProjectError } from './project-error';
import type { Project } from './project-file';
import { loadAutosave, recentProjects, recentText, remember, saveAutosave } from './project-store';
import type { RecentEntry } from './recent-list';

const AUTOSAVE_DELAY_MS = 1000;

// The file format loads when a project is first kept, opened or restored: it is not in the first load.
const encodeProject = async (p: Project) => (await import('./project-file')).encodeProject(p);
const decodeProject = async (text: string) => (await import('./project-file')).decodeProject(text);

/** A file name from a project name: what a file system takes. */
export function fileNameFor(name: string): string {
  return `${name.replace(/[\\/:*?"<>|\u0000-\u001f]+/g, '_').trim() || 'project'}.uv-project.json`;
}

export class ProjectSession {
  name = $state('Untitled');
  /** What happened last: saved, opened, restored, made. */
  status = $state<string | null>(null);
  /** When the project was last autosaved. */
  autosavedAt = $state<Date | null>(null);
  error = $state<string | null>(null);
  recent = $state.raw<RecentEntry[]>([]);
  #timer: ReturnType<typeof setTimeout> | null = null;
  /** Autosave waits until the last session's project is restored, so it cannot overwrite it. */
  #ready = false;

  constructor(
    private readonly editor: () => GridEditor,
    private readonly replace: (ed: GridEditor) => void,
    private readonly control: JobControl,
  ) {}

  snapshot(): Project {
    const ed = this.editor();
    return {
      name: this.name,
      machine: ed.machine,
      exposure: { fullMs: this.control.fullMs, strategy: this.control.strategy, ...(this.control.doseMJcm2 !== null && { mJcm2: this.control.doseMJcm2 }) },
      polarity: ed.layer.polarity,
      paint: { cols: ed.grid.cols, rows: ed.grid.rows, cells: ed.grid.cells },
      objects: ed.layer.objects,
    };
  }

  /** Brings back what was being worked on when the app last closed; then autosave starts. */
  async start(restore: boolean): Promise<void> {
    try {
      const kept = restore ? await loadAutosave() : undefined;
      if (kept) {
        await this.#load(await decodeProject(kept.text));
        this.status = `Restored from the autosave of ${new Date(kept.savedAt).toLocaleString()}`;
      }
      this.recent = await recentProjects();
    } catch (e) {
      this.error = `The autosaved project could not be restored: ${(e as Error).message}`;
    }
    this.#ready = true;
  }

  /** After an edit: autosave once edits stop for a moment. */
  schedule(): void {
    if (!this.#ready) return;
    if (this.#timer) clearTimeout(this.#timer);
    this.#timer = setTimeout(() => void this.autosave(), AUTOSAVE_DELAY_MS);
  }

  async autosave(): Promise<void> {
    if (this.#timer) clearTimeout(this.#timer);
    this.#timer = null;
    try {
      await saveAutosave(this.name, await encodeProject(this.snapshot()));
      this.autosavedAt = new Date();
    } catch (e) {
      this.error = `Autosave failed: ${(e as Error).message}`;
    }
  }

  /** Before a job starts: the project as it will run is kept, to open again after an interruption. */
  async beforeJob(): Promise<void> {
    const text = await encodeProject(this.snapshot());
    await saveAutosave(this.name, text);
    await this.#remember(text, 'before a job');
    this.status = `Kept before the job at ${new Date().toLocaleTimeString()}`;
  }

  /** The project as a file to download. */
  async save(): Promise<{ fileName: string; blob: Blob }> {
    const text = await encodeProject(this.snapshot());
    await this.#remember(text, 'saved');
    this.status = `Saved as ${fileNameFor(this.name)}`;
    return { fileName: fileNameFor(this.name), blob: new Blob([text], { type: 'application/json' }) };
  }

  async openFile(file: File): Promise<void> {
    await this.#try(async () => {
      if (file.size > MAX_PROJECT_BYTES) throw new ProjectError(`the file is ${(file.size / 1048576).toFixed(0)} MB; a project is at most ${MAX_PROJECT_BYTES / 1048576} MB`);
      await this.#open(await file.text(), `Opened ${file.name}`);
    });
  }

  async openRecent(id: string): Promise<void> {
    await this.#try(async () => this.#open(await recentText(id), 'Opened from recent projects'));
  }

  /** Opens a project made here (the material test); the one open is kept among the recent first. */
  async openMade(p: Project, status: string): Promise<void> {
    await this.#try(async () => {
      await this.#setAside();
      await this.#load(p);
      this.status = status;
      await this.autosave();
    });
  }

  /** An empty bed for the machine; the project open is kept among the recent ones. */
  async newProject(machine: GridEditor['machine']): Promise<void> {
    await this.#try(async () => {
      await this.#setAside();
      this.replace(new GridEditor(machine));
      this.name = 'Untitled';
      this.status = 'New project';
      await this.autosave();
    });
  }

  async #open(text: string, status: string): Promise<void> {
    const p = await decodeProject(text); // a bad file throws here, before anything is replaced
    await this.#setAside(p.name);
    await this.#load(p);
    await this.#remember(text, 'opened');
    this.status = status;
    await saveAutosave(p.name, text); // the file as it came: no need to encode it again
    this.autosavedAt = new Date();
  }

  async #load(p: Project): Promise<void> {
    const bed = DoseGrid.sizeForBed(p.machine.bedMm, p.machine.pitchUm);
    if (bed.cols !== p.paint.cols || bed.rows !== p.paint.rows)
      throw new ProjectError(`paint is ${p.paint.cols} × ${p.paint.rows} cells, but its machine's bed makes ${bed.cols} × ${bed.rows}`);
    const ed = new GridEditor(p.machine, { cells: p.paint.cells, objects: p.objects, polarity: p.polarity });
    this.replace(ed);
    this.name = p.name;
    this.control.fullMs = p.exposure.fullMs;
    this.control.doseMJcm2 = p.exposure.mJcm2 ?? null;
    this.control.strategy = p.exposure.strategy;
    // Pictures and drawings are read after the project shows; each appears as it is ready.
    const artwork = new Map(p.objects.filter(isArtwork).map((o) => [o.src, o]));
    if (!artwork.size) return;
    const { readArtwork } = await import('../studio/objects/remote-artwork');
    for (const [src, o] of artwork)
      readArtwork(o).then((a) => ed.layer.addArtwork(src, a), (e) => (this.error = `A picture of the project could not be read: ${(e as Error).message}`));
  }

  /**
   * Keeps the project open among the recent ones before another replaces it, if anything is in it;
   * under a name of its own if the incoming project has the same name, so one does not replace the other.
   */
  async #setAside(incoming?: string): Promise<void> {
    if (this.editor().isEmpty) return;
    const name = incoming === this.name ? `${this.name} (set aside ${new Date().toLocaleTimeString()})` : this.name;
    await this.#remember(await encodeProject(this.snapshot()), 'set aside', name);
  }

  async #remember(text: string, why: RecentEntry['why'], name = this.name): Promise<void> {
    await remember(name, text, why);
    this.recent = await recentProjects();
  }

  async #try(f: () => Promise<void>): Promise<void> {
    this.error = null;
    try {
      await f();
    } catch (e) {
      this.error = e instanceof ProjectError ? `This project cannot be opened: ${e.message}` : (e as Error).message;
    }
  }
}
