// Gerber 2016's block apertures (%ABD12*% … %AB*%), which neither tracespace line reads: each block is cut from
// the file and plotted on its own, with the file's format and the apertures defined before it; the file keeps
// a stand-in aperture of the same number, whose flashes the artwork draws as the block's artwork moved there.

/** A file's text with its blocks cut out, and each block's own text, ready to plot, by aperture number. */
export interface CutBlocks {
  text: string;
  blocks: Map<string, { text: string; line: number }>;
}

const BLOCK = /%ABD0*(\d+)\*%([\s\S]*?)%AB\*%/g;
// What a block's contents rely on from before it: the format, units, macros, apertures and modes.
const CONTEXT = /%(?:FS|MO|AM|AD)[^%]*%|^[ \t]*G0*(?:70|71|74|75)\*/gm;

/** The tool name the plotter gives aperture D<n>. */
export const blockTool = (n: string): string => String(Number(n));

/** Null when the file has no block; throws for a block inside a block, which is not cut. */
export function cutBlocks(text: string): CutBlocks | null {
  if (!text.includes('%AB')) return null;
  const blocks = new Map<string, { text: string; line: number }>();
  let cut = '';
  let last = 0;
  for (const m of text.matchAll(BLOCK)) {
    if (m[2].includes('%AB')) throw new Error('a block aperture (%AB) inside another is not supported');
    cut += text.slice(last, m.index);
    const context = (cut.match(CONTEXT) ?? []).join('\n');
    blocks.set(blockTool(m[1]), { text: `${context}\n${m[2].trim()}\nM02*\n`, line: text.slice(0, m.index).split('\n').length - 1 });
    // A stand-in of the same number: the plotter flashes it where the file does, and the artwork puts the block there.
    cut += `%ADD${m[1]}C,0.001*%`;
    last = m.index + m[0].length;
  }
  cut += text.slice(last);
  if (cut.includes('%AB')) throw new Error('a block aperture (%AB) that is never closed');
  return { text: cut, blocks };
}
