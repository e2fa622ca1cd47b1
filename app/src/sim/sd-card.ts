// The simulated SD card: files by name, and the job checkpoint that survives a reset.

export interface Checkpoint {
  file: string;
  /** Stops completed so far. */
  done: number;
  stops: number;
  /** The Nano's start and exposure count after the last stop done (its `C` reply). */
  boot: number;
  fires: number;
}

export class SdCard {
  files = new Map<string, string>();
  checkpoint: Checkpoint | null = null;
  present = true;

  /** The stored name matching `name` without regard to case, as FAT matches names. */
  find(name: string): string | undefined {
    const upper = name.toUpperCase();
    for (const key of this.files.keys()) if (key.toUpperCase() === upper) return key;
    return undefined;
  }

  list(): [string, number][] {
    return Array.from(this.files.entries()).map(([name, text]) => [name, text.length]);
  }
}
