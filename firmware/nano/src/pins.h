// Printhead Nano pin map: the only place pins are named (protocol/nano.md "LED bits and pins").
#pragma once

// The four UV LEDs sit on PORTB bits 2-5 (D10-D13) so one port write switches them together.
#define PIN_LED0 10
#define LED_PORT PORTB
#define LED_DDR DDRB
#define LED_SHIFT 2          // LED bit i is PORTB bit (i + LED_SHIFT)
#define LED_PORT_MASK 0x3C   // PB2..PB5

#define PIN_PROBE_SERVO 3    // CR Touch servo signal
#define PIN_PROBE_SIGNAL 7   // CR Touch trigger output
#define PIN_NEOPIXEL 8
#define PIN_TEMP_FIRST A0    // TMP36 sensors on A0..A5
