// Mega 2560 + CNC shield V3 pin map: the only place pins are named. The shield's Uno-shaped header
// sits on the Mega's D2-D13 and A0-A5 (= D54-D59); its I2C pins are not the Mega's, so the OLED
// goes on D20/D21, and the SD card on the Mega's SPI header (D50-D53).
#pragma once

// Serial ports: Serial0 = USB host, Serial1 = printhead Nano (hw/nano_uart drives USART1), ESP on
// Serial2 or Serial3 (esp.port).

// Steppers (step and direction pins on ports, for the step interrupt's direct writes).
#define PIN_X_STEP 2   // PE4
#define PIN_Y_STEP 3   // PE5
#define PIN_Z_STEP 4   // PG5
#define PIN_X_DIR 5    // PE3
#define PIN_Y_DIR 6    // PH3
#define PIN_Z_DIR 7    // PH4
#define PIN_ENABLE 8   // PH5, low = drivers on
// Endstops: switches to ground with the pull-ups on, so closed reads low.
#define PIN_X_MIN 9    // PH6
#define PIN_Y_MIN 10   // PB4
#define PIN_Z_MIN 11   // PB5
// The shield's Abort, Hold and Resume inputs: stop (e-stop), pause/continue, home.
#define PIN_BUTTON_STOP 54   // A0
#define PIN_BUTTON_PAUSE 55  // A1
#define PIN_BUTTON_HOME 56   // A2
// A3 (57), the shield's coolant enable, is light.pin's default.
#define PIN_SD_CS 53
// The SSD1306 panel on the hardware TWI (hw/oled).
#define PIN_PANEL_SDA 20  // PD1
#define PIN_PANEL_SCL 21  // PD0

// Port bits for the step interrupt.
#define STEP_XY_PORT PORTE
#define STEP_X_BIT (1 << 4)
#define STEP_Y_BIT (1 << 5)
#define STEP_Z_PORT PORTG
#define STEP_Z_BIT (1 << 5)
#define DIR_X_PORT PORTE
#define DIR_X_BIT (1 << 3)
#define DIR_YZ_PORT PORTH
#define DIR_Y_BIT (1 << 3)
#define DIR_Z_BIT (1 << 4)
#define ENDSTOP_X_PIN PINH
#define ENDSTOP_X_BIT (1 << 6)
#define ENDSTOP_YZ_PIN PINB
#define ENDSTOP_Y_BIT (1 << 4)
#define ENDSTOP_Z_BIT (1 << 5)

// True for a pin that the shield, the UARTs, I2C, SPI or the buttons use: never a light.
inline bool pinTaken(unsigned pin) {
  return pin <= 21 || (pin >= 50 && pin <= 56);
}
