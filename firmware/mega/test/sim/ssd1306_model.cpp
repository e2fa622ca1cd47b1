// The SSD1306 model: the command decoder and display RAM of the datasheet's chapters 8-10.
#include "ssd1306_model.h"

#include "panel_font.h"

namespace {
// Bytes each command takes, its own included (datasheet table 9-1); 1 for the rest.
uint8_t commandLength(uint8_t c) {
  switch (c) {
    case 0x20: case 0x81: case 0x8d: case 0xa8: case 0xd3: case 0xd5: case 0xd9: case 0xda: case 0xdb:
      return 2;
    case 0x21: case 0x22: case 0xa3:
      return 3;
    case 0x29: case 0x2a:
      return 6;
    case 0x26: case 0x27:
      return 7;
    default:
      return 1;
  }
}
}  // namespace

bool Ssd1306Model::start(uint8_t address, bool read) {
  selected_ = address == kAddress && !read;
  control_ = true;
  return selected_;
}

bool Ssd1306Model::write(uint8_t b) {
  if (!selected_) return false;
  if (control_) {
    single_ = b & 0x80;
    dataMode_ = b & 0x40;
    control_ = false;
    return true;
  }
  if (dataMode_) data(b);
  else command(b);
  if (single_) control_ = true;
  return true;
}

void Ssd1306Model::stop() {
  if (selected_) writes_++;
  selected_ = false;
}

void Ssd1306Model::command(uint8_t b) {
  if (cmdLen_ == 0) cmdNeed_ = commandLength(b);
  cmd_[cmdLen_++] = b;
  if (cmdLen_ < cmdNeed_) return;
  cmdLen_ = 0;
  const uint8_t c = cmd_[0];
  if (c <= 0x0f) col_ = static_cast<uint8_t>((col_ & 0xf0) | c);
  else if (c <= 0x1f) col_ = static_cast<uint8_t>((col_ & 0x0f) | (c & 0x0f) << 4);
  else if (c == 0x20) mode_ = cmd_[1] & 3;
  else if (c == 0x21) {
    col_ = colStart_ = cmd_[1] & 127;
    colEnd_ = cmd_[2] & 127;
  } else if (c == 0x22) {
    page_ = pageStart_ = cmd_[1] & 7;
    pageEnd_ = cmd_[2] & 7;
  }
  else if (c == 0x8d) pump_ = cmd_[1] & 0x04;
  else if (c == 0xa0 || c == 0xa1) segRemap_ = c & 1;
  else if (c == 0xc0 || c == 0xc8) comReverse_ = c & 8;
  else if (c == 0xae || c == 0xaf) on_ = c & 1;
  else if (c >= 0xb0 && c <= 0xb7) page_ = c & 7;
}

void Ssd1306Model::data(uint8_t b) {
  ram_[page_][col_] = b;
  data_++;
  if (mode_ == 2) {  // page addressing: the column wraps within the page
    col_ = static_cast<uint8_t>((col_ + 1) & 127);
  } else if (mode_ == 0) {
    if (col_ < colEnd_) {
      col_++;
    } else {
      col_ = colStart_;
      page_ = page_ < pageEnd_ ? static_cast<uint8_t>(page_ + 1) : pageStart_;
    }
  } else {
    if (page_ < pageEnd_) {
      page_++;
    } else {
      page_ = pageStart_;
      col_ = col_ < colEnd_ ? static_cast<uint8_t>(col_ + 1) : colStart_;
    }
  }
}

std::string Ssd1306Model::row(uint8_t page) const {
  std::string out;
  for (int cell = 0; cell < 16; cell++) {
    char c = mega::glyphChar(&ram_[page & 7][cell * 8]);
    out += c ? c : kUnknown;
  }
  return out;
}
