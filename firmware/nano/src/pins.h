// Printhead Nano pin map: the only place pins are named (protocol/nano.md "LED bits and pins").
#pragma once
#include <avr/io.h>

// The four UV LEDs sit on PORTB bits 2-5 (D10-D13), so one port write switches them together.
// The LED driver inputs need pull-downs on the board, so the LEDs stay dark while the pins float.
#define LED_PORT PORTB
#define LED_DDR DDRB
#define LED_SHIFT 2          // LED bit i is PORTB bit (i + LED_SHIFT)
#define LED_PORT_MASK 0x3C   // PB2..PB5

// CR Touch servo signal on D3 (PD3).
#define SERVO_PORT PORTD
#define SERVO_DDR DDRD
#define SERVO_BIT 3

// CR Touch trigger output on D7 (PD7, PCINT23). High = triggered.
#define PROBE_PIN PIND
#define PROBE_BIT 7
#define PROBE_PCMSK PCMSK2
#define PROBE_PCINT PCINT23
#define PROBE_PCIE PCIE2
#define PROBE_vect PCINT2_vect

// WS2812 NeoPixel data on D8 (PB0); it shares PORTB with the LEDs, so it is driven with sbi/cbi only.
#define PIXEL_PORT PORTB
#define PIXEL_DDR DDRB
#define PIXEL_BIT 0

// TMP36 sensors on A0..A5 = ADC channels 0..5.
#define TEMP_FIRST_CHANNEL 0
