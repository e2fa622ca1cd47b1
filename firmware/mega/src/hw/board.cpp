// The CNC shield's pins as the command core's MachineIo.
#include "hw/board.h"

#include <Arduino.h>

#include "hw/stepper_timer.h"
#include "pins.h"

namespace mega {

void Board::begin() {
  digitalWrite(PIN_ENABLE, HIGH);  // drivers off until a move or M17
  pinMode(PIN_ENABLE, OUTPUT);
  pinMode(PIN_BUTTON_STOP, INPUT_PULLUP);
  pinMode(PIN_BUTTON_PAUSE, INPUT_PULLUP);
  pinMode(PIN_BUTTON_HOME, INPUT_PULLUP);
}

uint8_t Board::endstops() { return readEndstops(); }

void Board::invertDirections(uint8_t bits) { stepperInvert(bits); }

void Board::motorsEnabled(bool on) { digitalWrite(PIN_ENABLE, on ? LOW : HIGH); }

bool Board::light(uint8_t pin, bool on) {
  if (pinTaken(pin) || pin > 69) return false;
  pinMode(pin, OUTPUT);
  digitalWrite(pin, on ? HIGH : LOW);
  return true;
}

uint8_t Board::buttons() {
  uint8_t b = 0;
  if (digitalRead(PIN_BUTTON_STOP) == LOW) b |= 1;
  if (digitalRead(PIN_BUTTON_PAUSE) == LOW) b |= 2;
  if (digitalRead(PIN_BUTTON_HOME) == LOW) b |= 4;
  return b;
}

}  // namespace mega
