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

/** The card's files; `revision` counts every write and delete, so a host keeping the card knows when to keep it again. */
export class CardFiles extends Map<string, string> {
  revision = 0;

  override set(name: string, text: string): this {
    super.set(name, text);
    this.revision++;
    return this;
  }

  override delete(name: string): boolean {
    const had = super.delete(name);
    if (had) this.revision++;
    return had;
  }

  override clear(): void {
    super.clear();
    this.revision++;
  }
}

export class SdCard {
  readonly files = new CardFiles();
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
