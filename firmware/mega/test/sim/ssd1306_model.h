// A model of the SSD1306 as an I2C device, for the simavr rig and the host tests: it takes the
// bytes of each write, keeps the display RAM as the chip would (set-up commands, horizontal and
// page addressing), and reads the eight text rows back by matching each 8-column cell against the
// firmware's own font. Plain C++; board_sim wires it to simavr's TWI.
#pragma once
#include <cstdint>
#include <string>

class Ssd1306Model {
 public:
  static constexpr uint8_t kAddress = 0x3c;
  static constexpr char kUnknown = '\x7f';  // a cell that is no glyph of the font

  // A start with this 7-bit address and direction; true if the panel acknowledges.
  bool start(uint8_t address, bool read);
  // A byte of a write; true if acknowledged.
  bool write(uint8_t byte);
  void stop();

  // Row `page` as text: 16 characters, kUnknown where a cell shows no glyph.
  std::string row(uint8_t page) const;
  bool on() const { return on_; }
  bool chargePump() const { return pump_; }
  // Column 0 at the left and page 0 at the top on the common modules (A1 and C8 sent).
  bool upright() const { return segRemap_ && comReverse_; }
  uint32_t writes() const { return writes_; }    // completed write transactions
  uint32_t dataBytes() const { return data_; }   // display-RAM bytes written

 private:
  void command(uint8_t b);
  void data(uint8_t b);

  uint8_t ram_[8][128] = {};
  bool selected_ = false, control_ = false;  // addressed; the next byte is a control byte
  bool dataMode_ = false, single_ = false;   // D/C of the bytes that follow; Co: only one follows
  uint8_t cmd_[7] = {};
  uint8_t cmdLen_ = 0, cmdNeed_ = 0;
  uint8_t mode_ = 2;  // 0 horizontal, 1 vertical, 2 page (the reset default)
  uint8_t colStart_ = 0, colEnd_ = 127, pageStart_ = 0, pageEnd_ = 7;
  uint8_t col_ = 0, page_ = 0;
  bool on_ = false, pump_ = false, segRemap_ = false, comReverse_ = false;
  uint32_t writes_ = 0, data_ = 0;
};
