// Host tests of the printhead command brain with a fake of its drivers.
#include "printhead.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace nano;

namespace {

struct FakeIo : PrintheadIo {
  uint8_t lit = 0;
  std::vector<FirePlan> fired;
  int allOffs = 0;
  uint16_t servo = 0;
  bool probe = false;
  std::string out;
  void fire(const FirePlan& p) override {
    fired.push_back(p);
    lit = p.onMask;
  }
  void allOff() override {
    allOffs++;
    lit = 0;
  }
  uint8_t litMask() const override { return lit; }
  uint32_t lineUs = 0;  // when the latest W arrived, by this board's micros()
  uint32_t clockLineUs() override { return lineUs; }
  bool cut = false;  // the LEDs were cut, `cutTicks` after the on-edge or the chain's last event
  int32_t cutTicks = 0;
  bool takeCut(int32_t& t) override {
    t = cutTicks;
    bool was = cut;
    cut = false;
    return was;
  }
  bool late = false;  // the G's time 0 has gone by when the Nano takes it
  ScanStore* running = nullptr;
  bool startProgram(ScanStore& s) override {
    if (late) return false;
    running = &s;
    return true;
  }
  void servoPulse(uint16_t us) override { servo = us; }
  bool probeTriggered() override { return probe; }
  void reply(const char* t, uint8_t n) override { out.append(t, n); }
  // Every speed change the brain asked the UART for: baud, and whether after the queued reply.
  std::vector<std::pair<uint32_t, bool>> speeds;
  void linkSpeed(uint32_t baud, bool afterReply) override { speeds.emplace_back(baud, afterReply); }
};

const PrintheadConfig kConfig = {10000000, {{600, 600, 600, 600, 550, 550}, 50, 100, 1750}, "0.2.0"};

struct Head {
  FakeIo io;
  Printhead ph{io, kConfig};
  uint16_t mv[6] = {735, 740, 745, 750, 755, 760};
  Head() { ph.readings(mv); }
  void send(const std::string& l, uint32_t now = 0) { ph.line(l.data(), static_cast<uint8_t>(l.size()), false, now); }
  std::string take() {
    std::string s = io.out;
    io.out.clear();
    return s;
  }
};

}  // namespace

TEST(Printhead, AnswersTheTable) {
  Head h;
  h.send("S");
  EXPECT_EQ(h.take(), "S:0\n");
  h.send("T");
  EXPECT_EQ(h.take(), "T:23.5,24.0,24.5,25.0,25.5,26.0\n");
  h.io.probe = true;
  h.send("P");
  EXPECT_EQ(h.take(), "P:1\n");
  h.send("V");
  EXPECT_EQ(h.take(), "V:1,0.2.0\n");
  h.send("E");
  EXPECT_EQ(h.take(), "E:0\n");
  h.io.lineUs = 4294967295u;  // the clock the Mega measures: micros() as the W arrived, wrapped or not
  h.send("W");
  EXPECT_EQ(h.take(), "W:4294967295\n");
  for (const char* silent : {"F:1,100,0,0,0", "R", "D", "U", "X"}) {
    h.send(silent);
    EXPECT_EQ(h.take(), "") << silent;
  }
}

TEST(Printhead, FiresPlansAndReportsLitLeds) {
  Head h;
  h.send("F:15,100,200,300,400");
  ASSERT_EQ(h.io.fired.size(), 1u);
  EXPECT_EQ(h.io.fired[0].onMask, 15);
  h.send("S");
  EXPECT_EQ(h.take(), "S:15\n");
  h.send("R");
  EXPECT_EQ(h.io.allOffs, 1);
  h.send("S");
  EXPECT_EQ(h.take(), "S:0\n");
}

TEST(Printhead, RefusesFireWhileBusyCappedOrFaultedAndLatchesWhy) {
  Head h;
  h.send("F:1,100,0,0,0");
  h.send("F:2,0,100,0,0");  // LED 0 still on
  EXPECT_EQ(h.io.fired.size(), 1u);
  h.io.lit = 0;
  h.send("F:1,10000001,0,0,0");
  EXPECT_EQ(h.io.fired.size(), 1u);
  h.send("E");
  EXPECT_EQ(h.take(), "E:12\n");  // BUSY | CAPPED
  h.send("E");
  EXPECT_EQ(h.take(), "E:0\n");  // latched bits clear once reported
  h.mv[3] = 500 + 700;
  h.ph.readings(h.mv);
  h.send("F:1,100,0,0,0");
  EXPECT_EQ(h.io.fired.size(), 1u);
  h.send("E");
  EXPECT_EQ(h.take(), "E:17\n");  // OVERTEMP (active) | REFUSED
  h.send("E");
  EXPECT_EQ(h.take(), "E:1\n");  // still hot
}

TEST(Printhead, CountsItsExposuresAndSaysWhetherTheLastRanWhole) {
  Head h;
  h.ph.setBoot(17);
  h.send("C");
  EXPECT_EQ(h.take(), "C:17,0,1\n");
  h.send("F:1,100,0,0,0");
  h.io.lit = 0;  // its timer switched it off
  h.send("F:2,0,100,0,0");
  h.io.lit = 0;
  h.send("F:0,0,0,0,0");          // lights nothing: not counted
  h.send("F:1,10000001,0,0,0");   // refused: not counted
  h.send("C");
  EXPECT_EQ(h.take(), "C:17,2,1\n");
  h.send("F:4,0,0,5000,0");
  h.send("R");  // cut short
  h.send("C");
  EXPECT_EQ(h.take(), "C:17,3,0\n");
  h.send("R");  // nothing lit: the last exposure's verdict stays
  h.send("F:8,0,0,0,5000");
  h.mv[0] = 500 + 700;  // over-temperature cuts it
  h.ph.readings(h.mv);
  h.send("C");
  EXPECT_EQ(h.take(), "C:17,4,0\n");
}

TEST(Printhead, NoFireBeforeTheFirstReadings) {
  FakeIo io;
  Printhead ph(io, kConfig);
  ph.line("F:1,100,0,0,0", 13, false, 0);
  EXPECT_TRUE(io.fired.empty());
}

TEST(Printhead, FaultDuringAFireCutsEveryLed) {
  Head h;
  h.send("F:15,5000000,5000000,5000000,5000000");
  h.mv[5] = 50;  // sensor 5 opens
  h.ph.readings(h.mv);
  EXPECT_EQ(h.io.allOffs, 1);
  EXPECT_EQ(h.io.lit, 0);
  h.send("E");
  EXPECT_EQ(h.take(), "E:130\n");  // SENSOR | CUTOFF
}

TEST(Printhead, MalformedLinesDoNothingButLatch) {
  Head h;
  h.send("F:16,1,1,1,1");
  h.send("s");
  h.ph.line("S", 1, true, 0);  // overlong
  h.send("");                  // empty: ignored, no flag
  EXPECT_TRUE(h.io.fired.empty());
  EXPECT_EQ(h.take(), "");
  h.send("E");
  EXPECT_EQ(h.take(), "E:32\n");
  h.send("S");
  EXPECT_EQ(h.take(), "S:0\n");
}

TEST(Printhead, ProbeServoWidths) {
  Head h;
  h.send("D");
  EXPECT_EQ(h.io.servo, 647);
  h.send("U");
  EXPECT_EQ(h.io.servo, 1473);
  h.send("X");
  EXPECT_EQ(h.io.servo, 2194);
}

TEST(Printhead, PixelFlashesTheCommandColourThenIdles) {
  Head h;
  EXPECT_EQ(h.ph.colour(0), uv::Colour::Green);
  h.send("F:1,10,0,0,0", 1000);
  EXPECT_EQ(h.ph.colour(1000), uv::Colour::Purple);
  EXPECT_EQ(h.ph.colour(1059), uv::Colour::Purple);
  h.io.lit = 0;  // the exposure ended
  EXPECT_EQ(h.ph.colour(1060), uv::Colour::Green);
  h.send("R", 2000);
  EXPECT_EQ(h.ph.colour(2010), uv::Colour::Orange);
  h.send("Z", 2020);  // malformed: no flash
  EXPECT_EQ(h.ph.colour(2030), uv::Colour::Orange);
  h.mv[0] = 500 + 650;
  h.ph.readings(h.mv);
  EXPECT_EQ(h.ph.colour(3000), uv::Colour::Red);
  h.send("T", 3000);
  EXPECT_EQ(h.ph.colour(3001), uv::Colour::DimWhite);
  EXPECT_EQ(h.ph.colour(3100), uv::Colour::Red);
  // A flash does not come back when the millisecond clock wraps around.
  EXPECT_EQ(h.ph.colour(3000 + 0x80000000u), uv::Colour::Red);
}

TEST(Printhead, APollRightAfterFDoesNotHideTheExposure) {
  // The Mega polls S straight after F: its dim white once replaced the purple before the pixel
  // was ever written, so no exposure showed.
  Head h;
  h.send("F:1,5000,0,0,0", 1000);
  h.send("S", 1000);
  EXPECT_EQ(h.ph.colour(1000), uv::Colour::Purple);
  EXPECT_EQ(h.ph.colour(1004), uv::Colour::Purple);
  h.io.lit = 0;  // 5 ms later the LED is off; the F's flash still runs its time
  h.send("S", 1006);
  EXPECT_EQ(h.ph.colour(1006), uv::Colour::Purple);
  EXPECT_EQ(h.ph.colour(1060), uv::Colour::Green);
  h.send("F:1,5000,0,0,0", 2000);
  h.send("R", 2001);  // R's orange replaces it: the LEDs are dark
  EXPECT_EQ(h.ph.colour(2001), uv::Colour::Orange);
  h.send("T", 2100);
  EXPECT_EQ(h.ph.colour(2100), uv::Colour::DimWhite);  // with nothing lit, a poll flashes as ever
}

namespace {
std::string loadLines(const std::vector<std::pair<uint32_t, uint8_t>>& ev, uint8_t flags) {
  uint16_t c = uv::kCheckInit;
  std::string a = "A:0";
  for (auto& e : ev) {
    a += "," + std::to_string(e.first) + "," + std::to_string(e.second);
    c = uv::checkEvent(c, e.first, e.second);
  }
  return a + "\nK:" + std::to_string(flags) + "," + std::to_string(ev.size()) + "," + std::to_string(c);
}
void sendLines(Head& h, const std::string& text) {
  size_t at = 0;
  while (at <= text.size()) {
    size_t nl = text.find('\n', at);
    if (nl == std::string::npos) nl = text.size();
    h.send(text.substr(at, nl - at));
    at = nl + 1;
  }
}
}  // namespace

TEST(PrintheadScan, LoadsSealsStartsAndReports) {
  Head h;
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:2,0,0\n");
  sendLines(h, loadLines({{0, 1}, {2000, 0}}, 0));
  EXPECT_EQ(h.take(), "K:0\n");
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:1,1,0\n");
  h.send("G");
  ASSERT_NE(h.io.running, nullptr);
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:1,0,1\n");  // the running program holds its buffer
  EXPECT_EQ(h.ph.colour(0), uv::Colour::Purple);  // a pass shows purple even between lit cells
  h.send("F:1,10,0,0,0");                          // no F while a pass runs
  EXPECT_TRUE(h.io.fired.empty());
  h.send("G");                                     // nor a second chain, and Q keeps telling this one
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:1,0,1\n");
  h.send("C");
  EXPECT_EQ(h.take(), "C:0,1,1\n");               // the pass counts as an exposure
  uint32_t d;
  uint8_t m;
  while (h.io.running->next(d, m) == ScanStore::Step::Event) {
  }
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:2,0,2\n");
  h.send("E");
  EXPECT_EQ(h.take(), "E:8\n");                   // BUSY from the F
}

TEST(PrintheadScan, RefusesAStartItCannotKeep) {
  Head h;
  h.send("G");  // nothing armed
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:2,0,6\n");
  sendLines(h, loadLines({{0, 1}, {2000, 0}}, 0));
  h.take();
  h.io.late = true;  // time 0 has gone by: the chain is dropped, not run late
  h.send("G");
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:2,0,6\n");
  h.io.late = false;
  sendLines(h, loadLines({{0, 1}, {2000, 0}}, 0));
  h.take();
  uint16_t hot[6] = {1200, 740, 745, 750, 755, 760};  // 70 °C on sensor 0
  h.ph.readings(hot);
  h.send("G");
  EXPECT_EQ(h.io.running, nullptr);
  h.send("E");
  EXPECT_EQ(h.take(), "E:17\n");  // OVERTEMP, REFUSED
}

TEST(PrintheadScan, ResetAndFaultsCutARunningPass) {
  Head h;
  sendLines(h, loadLines({{0, 1}, {2000, 0}}, 0));
  h.take();
  h.send("G");
  h.io.lit = 1;
  h.send("R");
  EXPECT_EQ(h.io.lit, 0);
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:2,0,3\n");
  h.send("C");
  EXPECT_EQ(h.take(), "C:0,1,0\n");
  sendLines(h, loadLines({{0, 1}, {2000, 0}}, 0));
  h.take();
  h.send("G");
  uint16_t hot[6] = {1200, 740, 745, 750, 755, 760};
  h.ph.readings(hot);  // no LED lit at this instant, but the pass is cut all the same
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:2,0,4\n");
  h.send("E");
  EXPECT_EQ(h.take(), "E:129\n");  // OVERTEMP, CUTOFF
}

TEST(PrintheadScan, AMalformedProgramLineIsLatchedAndSpoilsTheLoad) {
  Head h;
  h.send("A:0,0,1,5,0", 1000);
  EXPECT_EQ(h.ph.colour(1001), uv::Colour::DimWhite);
  h.send("A:1,5,99", 2000);
  EXPECT_EQ(h.ph.colour(2001), uv::Colour::Green);  // a malformed line flashes nothing
  h.send("K:0,2,1");
  EXPECT_EQ(h.take(), "K:1\n");
  h.send("K:4,2,1");  // flags over 3
  h.send("E");
  EXPECT_EQ(h.take(), "E:32\n");
}

TEST(PrintheadScan, AChainWhoseMegaFallsSilentIsCut) {
  Head h;
  sendLines(h, loadLines({{0, 1}, {200000, 0}}, 0));
  h.take();
  h.send("G", 1000);
  h.io.lit = 1;
  h.ph.poll(1030);
  h.send("Q", 1040);  // the Mega's poll keeps it alive
  h.take();
  h.ph.poll(1090);
  EXPECT_EQ(h.io.lit, 1);
  h.ph.poll(1091);  // 51 ms after the last line
  EXPECT_EQ(h.io.lit, 0);
  h.send("Q");
  EXPECT_EQ(h.take(), "Q:2,0,7\n");
  h.send("C");
  EXPECT_EQ(h.take(), "C:0,1,0\n");
}

// protocol/nano.md "Link speed": L is answered at the old speed, the UART changes after that reply,
// and the raised speed holds only once a correct line is heard at it within 100 ms.
TEST(PrintheadLinkSpeed, RaisedAfterTheReplyAndHeldOnceConfirmed) {
  Head h;
  h.send("L:250000", 1000);
  EXPECT_EQ(h.take(), "L:250000\n");
  ASSERT_EQ(h.io.speeds.size(), 1u);
  EXPECT_EQ(h.io.speeds[0], std::make_pair(250000u, true));
  EXPECT_TRUE(h.ph.linkRaised());
  h.send("V", 1010);  // the Mega's probe at the new speed
  EXPECT_EQ(h.take(), "V:1,0.2.0\n");
  h.ph.poll(1500);  // long past the 100 ms: confirmed, so it holds
  EXPECT_TRUE(h.ph.linkRaised());
  EXPECT_EQ(h.io.speeds.size(), 1u);
}

TEST(PrintheadLinkSpeed, NoLineHeardAtTheNewSpeedFallsBack) {
  Head h;
  h.send("L:1000000", 1000);
  h.take();
  h.ph.poll(1100);  // 100 ms: not yet
  EXPECT_TRUE(h.ph.linkRaised());
  h.ph.poll(1101);
  EXPECT_FALSE(h.ph.linkRaised());
  EXPECT_EQ(h.io.speeds.back(), std::make_pair(115200u, false));  // at once: nothing to answer
}

TEST(PrintheadLinkSpeed, NoiseOrAMalformedLineAboveTheStartSpeedFallsBackAndCutsTheLight) {
  for (int how = 0; how < 2; how++) {
    Head h;
    h.send("L:500000", 0);
    h.send("V", 1);
    h.send("F:1,5000000,0,0,0", 2);
    ASSERT_EQ(h.io.lit, 1);
    int offs = h.io.allOffs;
    if (how == 0) h.ph.noise();  // a byte with a framing error: the Mega is at another speed
    else h.send("S\x01", 3);     // a line that arrived misread
    EXPECT_FALSE(h.ph.linkRaised()) << how;
    EXPECT_EQ(h.io.lit, 0) << how;  // any doubt is an R: every LED off
    EXPECT_GT(h.io.allOffs, offs);
    h.take();
    h.send("C", 4);
    EXPECT_EQ(h.take(), "C:0,1,0\n") << "the exposure was cut";
  }
  Head h;  // at 115200 noise is only a malformed line's, and changes no speed
  h.ph.noise();
  h.send("S\x01");
  EXPECT_TRUE(h.io.speeds.empty());
}

TEST(PrintheadLinkSpeed, AnRReturnsTo115200AtOnce) {
  Head h;
  h.send("L:250000", 0);
  h.send("V", 1);
  h.send("R", 2);
  EXPECT_FALSE(h.ph.linkRaised());
  EXPECT_EQ(h.io.speeds.back(), std::make_pair(115200u, false));
}

TEST(PrintheadLinkSpeed, RefusedWhileExposingOrArmedAndOutOfTheTable) {
  Head h;
  h.send("F:1,5000000,0,0,0");
  h.send("E");
  h.take();
  h.send("L:250000");
  EXPECT_EQ(h.take(), "");  // no reply, no change: BUSY
  EXPECT_TRUE(h.io.speeds.empty());
  h.send("E");
  EXPECT_EQ(h.take(), "E:8\n");
  h.send("R");
  for (const char* bad : {"L:9600", "L:250001", "L:4295217296", "L:"}) {
    h.send(bad);
    EXPECT_EQ(h.take(), "") << bad;
  }
  EXPECT_TRUE(h.io.speeds.empty());
  h.send("E");
  EXPECT_EQ(h.take(), "E:32\n");
}

TEST(Printhead, ReportsEachFsDoseOnceItHasGoneDark) {
  Head h;
  h.send("O");
  EXPECT_EQ(h.take(), "O:0\n");
  h.send("F:5,300,0,120,0");
  ASSERT_EQ(h.io.fired.size(), 1u);
  h.send("O");
  EXPECT_EQ(h.take(), "O:0\n");  // still lit: no record yet
  h.io.lit = 0;  // the timer's last off
  h.send("O");
  EXPECT_EQ(h.take(), "O:1,0,300,0,120,0\n");  // exposure 1, as C counts it
  h.send("O");
  EXPECT_EQ(h.take(), "O:0\n");
}

TEST(Printhead, ACutFReportsWhatRanBeforeTheCut) {
  Head h;
  h.send("F:15,1000,50,2000,400");
  h.io.cut = true;  // the R's receive interrupt cut it 500.3 µs after the on-edge
  h.io.cutTicks = 500 * 16 + 5;
  h.io.lit = 0;
  h.send("R");
  h.send("O");
  EXPECT_EQ(h.take(), "O:1,0,500,50,500,400\n");
}

TEST(Printhead, AChainReportsEachProgramAndACutOnesPart) {
  Head h;
  // Program 0: LED 0 on at 100 µs, LED 1 too at 300, LED 0 off at 700 (LED 1 runs on); more follows.
  h.send("A:0,100,1,200,3,400,2");
  h.send("K:2,3," + std::to_string(uv::checkEvent(uv::checkEvent(uv::checkEvent(uv::kCheckInit, 100, 1), 200, 3), 400, 2)));
  EXPECT_EQ(h.take(), "K:0\n");
  // Program 1 continues: LED 1 off 250 µs on, LED 2 on 100 later, off 1000 later.
  h.send("A:0,250,0,100,4,1000,0");
  h.send("K:1,3," + std::to_string(uv::checkEvent(uv::checkEvent(uv::checkEvent(uv::kCheckInit, 250, 0), 100, 4), 1000, 0)));
  EXPECT_EQ(h.take(), "K:0\n");
  h.send("G");
  ASSERT_NE(h.io.running, nullptr);
  uint32_t d;
  uint8_t m;
  for (int e = 0; e < 3; e++) ASSERT_EQ(h.io.running->next(d, m), ScanStore::Step::Event);  // program 0 ran
  ASSERT_EQ(h.io.running->next(d, m), ScanStore::Step::Event);  // program 1's first event taken
  h.send("O");
  EXPECT_EQ(h.take(), "O:1,0,600,400,0,0\n");
  ASSERT_EQ(h.io.running->next(d, m), ScanStore::Step::Event);  // LED 1 off made; LED 2 on pending
  ASSERT_EQ(h.io.running->next(d, m), ScanStore::Step::Event);  // LED 2 on made; its off pending
  h.io.cut = true;  // a fault cut it 40 µs after LED 2 went on
  h.io.cutTicks = 40 * 16;
  h.send("R");
  h.send("O");
  EXPECT_EQ(h.take(), "O:1,1,0,250,40,0\n");
  h.send("O");
  EXPECT_EQ(h.take(), "O:0\n");
}
