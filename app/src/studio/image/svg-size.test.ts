import { describe, expect, it } from 'vitest';
import { svgSize } from './svg-size';

const svg = (attrs: string, body = '<rect width="1" height="1"/>') => `<?xml version="1.0"?>\n<!-- a board -->\n<svg xmlns="http://www.w3.org/2000/svg" ${attrs}>${body}</svg>`;

describe('an SVG drawing\'s stated size', () => {
  it('takes width and height in physical units', () => {
    expect(svgSize(svg('width="30mm" height="20mm" viewBox="0 0 30 20"')).mm).toEqual({ x: 30, y: 20 });
    expect(svgSize(svg('width="3cm" height="2cm"')).mm).toEqual({ x: 30, y: 20 });
    const inch = svgSize(svg("width='1.5in' height='0.5in'")).mm!;
    expect(inch.x).toBeCloseTo(38.1, 9);
    expect(inch.y).toBeCloseTo(12.7, 9);
    const points = svgSize(svg('width="72pt" height="6pc"')).mm!;
    expect([points.x, points.y].map((v) => +v.toFixed(9))).toEqual([25.4, 25.4]);
  });

  it('gives the other side from the viewBox when one side is physical', () => {
    expect(svgSize(svg('width="40mm" viewBox="0 0 400 100"')).mm).toEqual({ x: 40, y: 10 });
    expect(svgSize(svg('height="10mm" viewBox="0,0,400,100"')).mm).toEqual({ x: 40, y: 10 });
  });

  it('has no size in mm from pixels, a unitless size or a viewBox alone, only pixels for a resolution to turn into mm', () => {
    for (const attrs of ['width="120" height="80"', 'width="120px" height="80px"', 'viewBox="0 0 120 80"', 'width="100%" height="100%" viewBox="0 0 120 80"', 'width="120px" viewBox="0 0 3 2"']) {
      const s = svgSize(svg(attrs));
      expect(s.mm, attrs).toBeNull();
      expect(s.px, attrs).toEqual({ x: 120, y: 80 });
    }
  });

  it('reads only the root\'s own width, not a stroke-width, and keeps quotes holding ">"', () => {
    expect(svgSize(svg('stroke-width="3" data-note="a > b" width="10mm" height="5mm"')).mm).toEqual({ x: 10, y: 5 });
  });

  it('refuses what is not an SVG drawing or states no size', () => {
    expect(() => svgSize('<html><body>hi</body></html>')).toThrow(/not an SVG drawing/);
    expect(() => svgSize(svg('class="x"'))).toThrow(/states no size/);
    expect(() => svgSize(svg('width="0mm" height="-2mm"'))).toThrow(/states no size/);
  });

  it('rewrites the root for drawing: its size in pixels, a viewBox where it had none, everything else kept', () => {
    const s = svgSize(svg('width="25.4mm" height="12.7mm" fill="red"', '<circle r="3"/>'));
    expect(s.renderable).toContain('<svg xmlns="http://www.w3.org/2000/svg" fill="red" width="96" height="48" viewBox="0 0 96 48"><circle r="3"/></svg>');
    expect(s.renderable.startsWith('<?xml version="1.0"?>\n<!-- a board -->\n')).toBe(true);
    const kept = svgSize(svg('width="30mm" height="20mm" viewBox="-5 -5 30 20" preserveAspectRatio="none"')).renderable;
    expect(kept).toMatch(/viewBox="-5 -5 30 20" preserveAspectRatio="none" width="113\.3\d*" height="75\.5\d*">/);
    expect(svgSize('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 4 2"/>').renderable).toBe('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 4 2" width="4" height="2"/>');
  });
});
