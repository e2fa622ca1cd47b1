// An imported picture as what the printer needs: one grey level per pixel, 0 black to 255 white.

export interface Gray {
  width: number;
  height: number;
  /** width × height values, row 0 first: 0 black … 255 white. */
  values: Uint8Array;
}

/**
 * RGBA pixels (a canvas's ImageData) to grey by Rec. 709 luma, each pixel laid on white by its
 * alpha: a transparent logo background is white, i.e. not exposed.
 */
export function toGray(rgba: Uint8ClampedArray | Uint8Array, width: number, height: number): Gray {
  const values = new Uint8Array(width * height);
  for (let i = 0, p = 0; i < values.length; i++, p += 4) {
    const a = rgba[p + 3] / 255;
    const luma = 0.2126 * rgba[p] + 0.7152 * rgba[p + 1] + 0.0722 * rgba[p + 2];
    values[i] = Math.round(luma * a + 255 * (1 - a));
  }
  return { width, height, values };
}

/**
 * Resamples to a grid size: each cell the mean of the source pixels it covers (a box filter,
 * so a finely hatched area keeps its overall darkness), or the nearest pixel when enlarging.
 */
export function resample(src: Gray, width: number, height: number): Gray {
  const values = new Uint8Array(width * height);
  const sx = src.width / width, sy = src.height / height;
  for (let y = 0; y < height; y++) {
    const y0 = y * sy, y1 = (y + 1) * sy;
    for (let x = 0; x < width; x++) {
      const x0 = x * sx, x1 = (x + 1) * sx;
      let sum = 0, area = 0;
      for (let py = Math.floor(y0); py < Math.min(Math.ceil(y1), src.height); py++) {
        const wy = Math.min(py + 1, y1) - Math.max(py, y0);
        for (let px = Math.floor(x0); px < Math.min(Math.ceil(x1), src.width); px++) {
          const w = wy * (Math.min(px + 1, x1) - Math.max(px, x0));
          sum += w * src.values[py * src.width + px];
          area += w;
        }
      }
      // Half a level rounds towards black: a cell covered exactly half is half dark, as a threshold of 50 % reads it.
      values[y * width + x] = area > 0 ? 255 - Math.round(255 - sum / area) : 255;
    }
  }
  return { width, height, values };
}

/**
 * Whether a picture is line art (a board's copper, a logo): nearly every pixel black or white, the
 * greys only the anti-aliased edges. Line art is exposed by a coverage threshold; a photograph is dithered.
 */
export function isLineArt(src: Gray): boolean {
  let grey = 0;
  for (const v of src.values) if (v > 24 && v < 231) grey++;
  return grey <= src.values.length * 0.05;
}
