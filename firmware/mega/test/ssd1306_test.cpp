// The panel's driver logic on the host: the font, the frames the SSD1306 gets (read back through
// the rig's SSD1306 model), the TWI interrupt's steps, and what a panel that stops answering costs.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "sim/ssd1306_model.h"
#include "panel_font.h"
#include "ssd1306.h"
#include "twi_write.h"

using namespace mega;

namespace {

// Sends every frame the driver has now through a TwiWrite, as the interrupt would, into the model.
int sendAll(Ssd1306& panel, Ssd1306Model& model, uint32_t nowMs = 0) {
  PanelFrame f;
  int frames = 0;
  while (panel.next(f, nowMs)) {
    frames++;
    EXPECT_LE(f.len, kFrameMax);
    TwiWrite w = {kPanelAddress, f.bytes, f.len, 0};
    uint8_t byte = 0;
    EXPECT_EQ(w.step(kTwiStart, byte), TwiWrite::Action::Send);
    EXPECT_TRUE(model.start(byte >> 1, byte & 1));
    TwiWrite::Action a;
    while ((a = w.step(kTwiDataAck, byte)) == TwiWrite::Action::Send) EXPECT_TRUE(model.write(byte));
    EXPECT_EQ(a, TwiWrite::Action::Stop);
    model.stop();
  }
  return frames;
}

}  // namespace

TEST(PanelFont, EveryPrintableCharacterHasItsOwnGlyphInFiveColumnsWithSpaceAround) {
  std::set<std::string> glyphs;
  for (char c = kFontFirst; c <= kFontLast; c++) {
    uint8_t cols[kGlyphWidth];
    for (uint8_t k = 0; k < kGlyphWidth; k++) cols[k] = glyphColumn(c, k);
    EXPECT_EQ(cols[0] | cols[6] | cols[7], 0) << c;  // neighbours never touch
    if (c != ' ') {
      EXPECT_NE(cols[1] | cols[2] | cols[3] | cols[4] | cols[5], 0) << c;
    }
    glyphs.insert(std::string(cols, cols + kGlyphWidth));
    EXPECT_EQ(glyphChar(cols), c);
  }
  EXPECT_EQ(glyphs.size(), 95u);
  uint8_t blank[kGlyphWidth] = {0, 0xff};
  EXPECT_EQ(glyphChar(blank), 0);
  EXPECT_EQ(glyphColumn('\n', 3), glyphColumn('?', 3));  // outside the font: '?'
}

TEST(PanelFont, GlyphsReadTopDownWithBitZeroAtTheTop) {
  // 'T': a full top row, then the stem in the middle column.
  EXPECT_EQ(glyphColumn('T', 1), 0x01);
  EXPECT_EQ(glyphColumn('T', 3), 0x7f);
  // '_' sits on the bottom row; ',' hangs into it, '.' does not.
  EXPECT_EQ(glyphColumn('_', 2), 0x80);
  EXPECT_EQ(glyphColumn(',', 2), 0x80 | 0x20);
  EXPECT_EQ(glyphColumn('.', 2), 0x40 | 0x20);
}

TEST(Ssd1306, SetsThePanelUpInTwoFramesThenDrawsARowInNine) {
  Ssd1306 panel;
  Ssd1306Model model;
  panel.begin();
  EXPECT_FALSE(panel.ready());
  EXPECT_EQ(sendAll(panel, model), 2);
  EXPECT_TRUE(panel.ready());
  EXPECT_TRUE(model.on());
  EXPECT_TRUE(model.chargePump());
  EXPECT_TRUE(model.upright());
  panel.show(3, "stop 120/4000   ");
  EXPECT_FALSE(panel.ready());
  EXPECT_EQ(sendAll(panel, model), 1 + 8);  // the address, then two characters a frame
  EXPECT_TRUE(panel.ready());
  EXPECT_EQ(model.row(3), "stop 120/4000   ");
  EXPECT_EQ(model.dataBytes(), 128u);
  panel.show(7, "~{Hello, World}`");
  sendAll(panel, model);
  EXPECT_EQ(model.row(7), "~{Hello, World}`");
  EXPECT_EQ(model.row(3), "stop 120/4000   ");  // the other rows untouched
  EXPECT_EQ(model.row(0), std::string(16, ' '));  // cleared RAM reads as spaces
}

TEST(Ssd1306, OneFrameAPassAtMost) {
  Ssd1306 panel;
  PanelFrame f;
  panel.begin();
  EXPECT_TRUE(panel.next(f, 0));
  EXPECT_EQ(f.bytes[0], 0x00);  // commands
  EXPECT_EQ(f.len, 17);
  EXPECT_EQ(f.bytes[1], 0xae);  // off while it is set up
  EXPECT_TRUE(panel.next(f, 0));
  EXPECT_EQ(f.len, 10);
  EXPECT_EQ(f.bytes[f.len - 1], 0xaf);  // on at the end
  EXPECT_FALSE(panel.next(f, 0));
}

TEST(Ssd1306, APanelThatStopsAnsweringIsSetUpAgainASecondLaterAndRedrawn) {
  Ssd1306 panel;
  Ssd1306Model model;
  PanelFrame f;
  panel.begin();
  sendAll(panel, model);
  panel.show(0, "UV ready        ");
  ASSERT_TRUE(panel.next(f, 100));
  panel.failed(100);
  EXPECT_TRUE(panel.takeLost());
  EXPECT_FALSE(panel.takeLost());  // once
  EXPECT_FALSE(panel.ready());
  EXPECT_FALSE(panel.next(f, 100 + kPanelRetryMs - 1));  // nothing on the bus meanwhile
  EXPECT_TRUE(panel.next(f, 100 + kPanelRetryMs));
  EXPECT_EQ(f.bytes[1], 0xae);  // the set-up from the top
  EXPECT_TRUE(panel.next(f, 100 + kPanelRetryMs));
  EXPECT_TRUE(panel.ready());
}

TEST(TwiWrite, SendsTheAddressThenEachByteThenStopsAndFailsOnAnyOtherStatus) {
  const uint8_t bytes[] = {0x40, 0x12, 0x34};
  TwiWrite w = {0x3c, bytes, 3, 0};
  uint8_t b = 0;
  EXPECT_EQ(w.step(kTwiStart, b), TwiWrite::Action::Send);
  EXPECT_EQ(b, 0x78);  // 0x3c, write
  EXPECT_EQ(w.step(kTwiAddressAck, b), TwiWrite::Action::Send);
  EXPECT_EQ(b, 0x40);
  EXPECT_EQ(w.step(kTwiDataAck | 0x03, b), TwiWrite::Action::Send);  // prescaler bits ignored
  EXPECT_EQ(b, 0x12);
  EXPECT_EQ(w.step(kTwiDataAck, b), TwiWrite::Action::Send);
  EXPECT_EQ(b, 0x34);
  EXPECT_EQ(w.step(kTwiDataAck, b), TwiWrite::Action::Stop);
  EXPECT_EQ(w.step(kTwiRepeatedStart, b), TwiWrite::Action::Send);  // from the top
  EXPECT_EQ(b, 0x78);
  for (uint8_t status : {0x20, 0x30, 0x38, 0x00, 0xf8}) {  // address or data not acknowledged, lost, bus error
    TwiWrite again = {0x3c, bytes, 3, 0};
    EXPECT_EQ(again.step(status, b), TwiWrite::Action::Fail) << int(status);
  }
}
