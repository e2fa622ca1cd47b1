// An SVG drawing's size as its root element states it: width and height in physical units (mm,
// cm, in, pt, pc, Q), or only in pixels or a viewBox, when the user is asked for a resolution. And
// the root rewritten so that, drawn into any box, the drawing fills it exactly.

export interface SvgSize {
  /** The size in mm the file states, or null when it gives only pixels or user units. */
  mm: { x: number; y: number } | null;
  /** Its size in CSS pixels (user units when unitless): what a resolution turns into mm when mm is null. */
  px: { x: number; y: number };
  /** The file with its root's width and height in pixels and a viewBox, for drawing at any size. */
  renderable: string;
}

const MM_PER: Record<string, number> = { mm: 1, cm: 10, q: 0.25, in: 25.4, pt: 25.4 / 72, pc: 25.4 / 6 };
/** CSS: 96 px to the inch. */
const PX_MM = 25.4 / 96;

type Length = { value: number; unit: string };

/** The root element's opening tag: quotes may hold '>'. */
const ROOT = /<svg\b((?:[^>"']|"[^"]*"|'[^']*')*)>/;
const attribute = (name: string) => new RegExp(`(?:^|\\s)${name}\\s*=\\s*(?:"([^"]*)"|'([^']*)')`);

function read(attrs: string, name: string): string | null {
  const m = attribute(name).exec(attrs);
  return m ? (m[1] ?? m[2]) : null;
}

function length(text: string | null): Length | null {
  const m = text && /^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:e[+-]?\d+)?)\s*(mm|cm|q|in|pt|pc|px|%|em|ex)?\s*$/i.exec(text);
  if (!m || !(Number(m[1]) > 0)) return null;
  return { value: Number(m[1]), unit: (m[2] ?? 'px').toLowerCase() };
}

const physical = (l: Length | null) => (l && l.unit in MM_PER ? l.value * MM_PER[l.unit] : null);
const pixels = (l: Length | null) => (l && l.unit === 'px' ? l.value : null);

function viewBox(text: string | null): { w: number; h: number } | null {
  const n = text?.trim().split(/[\s,]+/).map(Number);
  return n && n.length === 4 && n.every(Number.isFinite) && n[2] > 0 && n[3] > 0 ? { w: n[2], h: n[3] } : null;
}

/** The size an SVG file states; throws when it is not an SVG drawing or states no size at all. */
export function svgSize(text: string): SvgSize {
  const root = ROOT.exec(text);
  if (!root) throw new Error('this file is not an SVG drawing (no <svg> element)');
  const attrs = root[1];
  const w = length(read(attrs, 'width')), h = length(read(attrs, 'height'));
  const vb = viewBox(read(attrs, 'viewBox'));
  const aspect = vb ? vb.h / vb.w : null;

  // In mm: both sides physical, or one with the viewBox giving the other.
  let mmX = physical(w), mmY = physical(h);
  if (mmX !== null && mmY === null && aspect !== null && !pixels(h)) mmY = mmX * aspect;
  if (mmY !== null && mmX === null && aspect !== null && !pixels(w)) mmX = mmY / aspect;
  const mm = mmX !== null && mmY !== null ? { x: mmX, y: mmY } : null;

  let px: { x: number; y: number } | null = null;
  if (mm) px = { x: mm.x / PX_MM, y: mm.y / PX_MM };
  else {
    let x = pixels(w), y = pixels(h);
    if (x !== null && y === null && aspect !== null) y = x * aspect;
    if (y !== null && x === null && aspect !== null) x = y / aspect;
    if (x !== null && y !== null) px = { x, y };
    else if (vb) px = { x: vb.w, y: vb.h };
  }
  if (!px) throw new Error('this SVG states no size: its root has no width and height, and no viewBox');

  const rest = attrs.replace(new RegExp(attribute('(?:width|height)').source, 'g'), '').replace(/\/\s*$/, '');
  const end = /\/\s*$/.test(attrs) ? '/>' : '>';
  const box = vb ? '' : ` viewBox="0 0 ${px.x} ${px.y}"`; // no viewBox: one user unit is one pixel
  const renderable = text.slice(0, root.index) + `<svg${rest} width="${px.x}" height="${px.y}"${box}${end}` + text.slice(root.index + root[0].length);
  return { mm, px, renderable };
}
