// MD5 of a file, for checking what an ESP wrote: its ROM and stub answer SPI_FLASH_MD5 with the MD5
// of a flash region, which is compared with this one of the file, in place of reading it all back.
// Not for security: MD5 is what the ESP computes. spark-md5 does the hashing: the esp-flash chunk,
// which only the Firmware view loads, grew from 1.7 to 3.7 KB gzipped with it (`npm run build`).
import SparkMD5 from 'spark-md5';

export function md5Hex(data: Uint8Array): string {
  // spark-md5 hashes a whole ArrayBuffer: a view into a larger one (a part of a firmware bundle)
  // is copied out first.
  const whole = data.byteOffset === 0 && data.byteLength === data.buffer.byteLength && data.buffer instanceof ArrayBuffer;
  return SparkMD5.ArrayBuffer.hash(whole ? (data.buffer as ArrayBuffer) : data.slice().buffer);
}
