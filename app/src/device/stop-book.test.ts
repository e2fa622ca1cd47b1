import { describe, expect, it } from 'vitest';
import { StopBook } from './stop-book';

describe('StopBook', () => {
  it('gives the changes since a line, and starts again on a clear', () => {
    const book = new StopBook<string>();
    book.stops.set(3, 'a');
    book.changed(3);
    book.stops.set(5, 'b');
    book.changed(5);
    book.changed(3);
    expect(book.since(0)).toEqual({ stops: [3, 5, 3], lines: 3, clears: 0 });
    expect(book.since(2)).toEqual({ stops: [3], lines: 3, clears: 0 });
    book.clear();
    expect(book.stop(3)).toBeUndefined();
    expect(book.since(0)).toEqual({ stops: [], lines: 0, clears: 1 });
  });

  it('takes the clears it is told: a mirror follows its ledger', () => {
    const mirror = new StopBook<string>(-1);
    expect(mirror.clears).toBe(-1);
    mirror.clear(4);
    expect(mirror.since(0)).toEqual({ stops: [], lines: 0, clears: 4 });
  });
});
