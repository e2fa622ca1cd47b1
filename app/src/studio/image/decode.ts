// Decodes a picture file (JPG, PNG, GIF's first frame, BMP, anything the browser reads) to grey.

import { toGray, type Gray } from './gray';

export const IMAGE_TYPES = 'image/png,image/jpeg,image/gif,image/bmp,image/webp';

export async function decodeImage(file: Blob): Promise<Gray> {
  let bitmap: ImageBitmap;
  try {
    bitmap = await createImageBitmap(file);
  } catch {
    throw new Error('this file is not a picture the browser can read (JPG, PNG, GIF or BMP)');
  }
  const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
  const ctx = canvas.getContext('2d')!;
  ctx.drawImage(bitmap, 0, 0);
  bitmap.close();
  const data = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
  return toGray(data, canvas.width, canvas.height);
}
