// Deterministic test masks for benchmarks: PCB-like traces, sparse dots, fill, photo-like gradient, text-like blocks.

export type Mask = { name: string; cols: number; rows: number; cells: Uint8Array[] };

function rng(seed: number): () => number {
  let x = seed >>> 0 || 1;
  return () => {
    x ^= x << 13;
    x ^= x >>> 17;
    x ^= x << 5;
    return (x >>> 0) / 4294967296;
  };
}

function blank(cols: number, rows: number): Uint8Array[] {
  return Array.from({ length: rows }, () => new Uint8Array(cols));
}

/** A board at 50 µm cells: traces 6-14 cells (0.3-0.7 mm) wide, bends, and square pads. */
export function boardMask(cols: number, rows: number, seed = 4): Mask {
  const r = rng(seed);
  const cells = blank(cols, rows);
  const fill = (x0: number, y0: number, w: number, h: number) => {
    for (let y = Math.max(0, y0); y < Math.min(rows, y0 + h); y++)
      for (let x = Math.max(0, x0); x < Math.min(cols, x0 + w); x++) cells[y][x] = 255;
  };
  for (let t = 0; t < (cols * rows) / 6000; t++) {
    let x = Math.floor(r() * cols), y = Math.floor(r() * rows);
    const w = 6 + Math.floor(r() * 9);
    fill(x - 10, y - 10, 20 + w, 20 + w); // pad at the start
    for (let leg = 0; leg < 3; leg++) {
      const len = 40 + Math.floor(r() * 200);
      if (leg % 2 === 0) {
        const dir = r() < 0.5 ? -1 : 1;
        fill(dir > 0 ? x : x - len, y, len + w, w);
        x += dir * len;
      } else {
        const dir = r() < 0.5 ? -1 : 1;
        fill(x, dir > 0 ? y : y - len, w, len + w);
        y += dir * len;
      }
    }
    fill(x - 10, y - 10, 20 + w, 20 + w); // pad at the end
  }
  return { name: 'pcb', cols, rows, cells };
}

/** Horizontal and vertical one-cell traces with pads, about 15 % exposed. */
export function pcbMask(cols: number, rows: number, seed = 1): Mask {
  const r = rng(seed);
  const cells = blank(cols, rows);
  for (let t = 0; t < (cols * rows) / 400; t++) {
    const x = Math.floor(r() * cols), y = Math.floor(r() * rows), len = 10 + Math.floor(r() * 80);
    const vertical = r() < 0.5;
    for (let i = 0; i < len; i++) {
      const cx = vertical ? x : x + i, cy = vertical ? y + i : y;
      if (cx < cols && cy < rows) cells[cy][cx] = 255;
    }
  }
  return { name: 'pcb', cols, rows, cells };
}

export function sparseMask(cols: number, rows: number, seed = 2): Mask {
  const r = rng(seed);
  const cells = blank(cols, rows);
  for (let i = 0; i < (cols * rows) / 200; i++) cells[Math.floor(r() * rows)][Math.floor(r() * cols)] = 255;
  return { name: 'sparse', cols, rows, cells };
}

export function fillMask(cols: number, rows: number): Mask {
  return { name: 'fill', cols, rows, cells: Array.from({ length: rows }, () => new Uint8Array(cols).fill(255)) };
}

export function photoMask(cols: number, rows: number): Mask {
  const cells = blank(cols, rows);
  for (let y = 0; y < rows; y++)
    for (let x = 0; x < cols; x++) cells[y][x] = Math.round(127.5 + 127.5 * Math.sin(x / 37) * Math.cos(y / 23));
  return { name: 'photo', cols, rows, cells };
}

export function textMask(cols: number, rows: number, seed = 3): Mask {
  const r = rng(seed);
  const cells = blank(cols, rows);
  for (let line = 8; line + 12 < rows; line += 20)
    for (let x = 8; x + 6 < cols; x += 8)
      for (let dy = 0; dy < 12; dy++) for (let dx = 0; dx < 6; dx++) if (r() < 0.45) cells[line + dy][x + dx] = 255;
  return { name: 'text', cols, rows, cells };
}
