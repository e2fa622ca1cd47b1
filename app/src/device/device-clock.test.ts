import { describe, expect, it } from 'vitest';
import { DeviceClock } from './device-clock';

describe('DeviceClock', () => {
  it('runs at the printer\'s speed, and never back when the speed changes', () => {
    let wall = 1000;
    const clock = new DeviceClock(() => wall);
    expect(clock.nowS(20)).toBe(0);
    wall += 1000;
    expect(clock.nowS(20)).toBe(20); // one wall second of a simulated printer at 20×
    wall += 3000;
    expect(clock.nowS(1)).toBe(23); // then a real printer: on from where it was
    wall -= 500; // a clock that stepped back does not take the printer's time back
    expect(clock.nowS(1)).toBe(23);
  });
});
