// The Mega's side of the printhead link (protocol/nano.md): background temperature and fault polls,
// exposures (F, then S until the LEDs are off, then E to learn whether it was refused), the probe,
// and a Nano that stops answering. Every call returns at once.
#pragma once
#include <stdint.h>

#include "byte_stream.h"
#include "line_splitter.h"
#include "nano_clock.h"
#include "nano_codec.h"

namespace mega {

constexpr uint32_t kNanoReplyTimeoutUs = 50000;  // protocol/mega.md §6
constexpr uint8_t kNanoMissesOffline = 3;
constexpr uint32_t kThermalPollUs = 500000;
constexpr uint32_t kFaultPollUs = 500000;
constexpr uint32_t kFireGraceUs = 100000;  // LEDs still on this long after the longest duration: R
constexpr uint32_t kFireRepollUs = 250;       // an S that found an LED still on: ask again this soon
constexpr uint32_t kFireFirstCheckUs = 2000;
// The F's light starts when its line has crossed the wire (10 bits a byte) and the Nano has taken it
// (about 200 µs measured in simavr); the S that checks its end needs two byte-times to get there.
constexpr uint32_t kFireTakenUs = 300;
constexpr uint32_t kClockPollUs = 250000;    // W until the Nano's clock is known
constexpr uint32_t kClockRepollUs = 5000000;  // then now and then, to follow its drift
// The raised link speed (protocol/nano.md "Link speed", "Which speed"): the Nano's interrupts-off
// stretches fit three byte-times at 250000, not at 500000.
constexpr uint32_t kNanoFastBaud = 250000;
// Whether the board raises the link (once the Nano is known and the link idle).
constexpr bool kRaiseNanoLink = true;
// The fastest speed a job is planned at (uv::MotionModel::linkBaud; planner.md "The printhead link"). A job
// is planned at the speed the link has or will have (PrintheadLink::jobBaud()): this, or 115200 with a
// Nano that never takes L. The speed is kept with the job (the card's stop file, a stream's machine),
// and a scan pass starts only with the link at least that fast (ScanRun waits for the raise).
constexpr uint32_t kJobLinkBaud = kRaiseNanoLink ? kNanoFastBaud : uv::kNanoBaud;
constexpr uint32_t kWakeGapUs = 2000;  // after begin()'s 0x00, quiet so long before the R
constexpr uint32_t kSpeedRetryUs = 5000000;  // after a fall-back or an L unanswered, asked again so late

enum class FireState : uint8_t { Idle, Firing, Done, Failed };

class PrintheadLink {
 public:
  enum Event : uint8_t {
    kWentOffline = 1,  // three replies missed in a row: FAULT:E30
    kCameBack = 2,     // a reply after being offline
    kFault = 4,        // OVERTEMP or SENSOR became active, or CUTOFF latched
    kNanoReset = 8,    // the Nano's watchdog reset it (WATCHDOG latched)
  };

  explicit PrintheadLink(ByteStream& io)
      : io_(io), splitter_(line_, kReplyMax), online_(false), reportedOffline_(false), offPending_(false), identityWanted_(true),
        probeWanted_(false), probeAnswered_(false), probeTriggered_(false), countersWanted_(false), countersAnswered_(false), whole_(true),
        tempsKnown_(false), fireCheckWanted_(false), sealAnswered_(false), passWanted_(false), passAnswered_(false), held_(false), doseHeld_(false),
        raise_(false), raiseSoon_(false), raiseFailed_(false), doseWanted_(false) {}

  // The sink, given to poll() (not kept: the Mega's RAM), takes a record, or, given nullptr, says
  // whether it could take one now (its line has room to go out whole): O waits until it can, as the
  // Nano keeps its records meanwhile.
  struct DoseSink {
    bool (*take)(void* ctx, const uv::NanoReply* record);
    void* ctx;
  };

  // After the Mega starts: LEDs off (R), then identify the Nano (V).
  void begin(uint32_t nowUs);
  void poll(uint32_t nowUs, DoseSink dose = {nullptr, nullptr});

  // All LEDs off now (R), ahead of anything queued. Ends a running exposure as Failed.
  void allOff(uint8_t why = 0);
  // Starts an exposure. False if one is running, the Nano is offline, or the UART is full.
  bool fire(uint8_t mask, const uint32_t us[uv::kLedCount], uint32_t nowUs);
  FireState fireState() const { return fire_; }
  // Why the exposure failed: 30 (no answer), 31 (cut off by over-temperature), 33 (refused),
  // or what allOff() was given.
  uint8_t fireError() const { return fireError_; }
  // The E flags that explained a refusal (CAPPED, BUSY, REFUSED).
  uint8_t fireFlags() const { return fireFlags_; }
  void clearFire() { fire_ = FireState::Idle; }

  // CR Touch: 'D' deploy, 'U' stow, 'X' alarm release. False if the UART is full.
  bool servo(char op);
  // Asks P; probeAnswered() turns true with the reply.
  void requestProbe() {
    probeWanted_ = true;
    probeAnswered_ = false;
  }
  bool probeAnswered() const { return probeAnswered_; }
  bool probeTriggered() const { return probeTriggered_; }
  // Asks C: the Nano's start number, its exposure count and whether the last one ran whole.
  void requestCounters() {
    countersWanted_ = true;
    countersAnswered_ = false;
  }
  bool countersAnswered() const { return countersAnswered_; }
  uint16_t boot() const { return boot_; }
  uint32_t fires() const { return fires_; }
  bool lastWhole() const { return whole_; }

  // Scan programs (protocol/nano.md "Scan programs"). A line of the chain, with its '\n' (from
  // uv::ProgramLines): an A line goes out at once; a K line waits for its answer, so it needs the
  // link free of requests too. False when it cannot go now: try again later.
  bool programLine(const char* line, uint8_t len, uint32_t nowUs);
  bool sealAnswered() const { return sealAnswered_; }
  // The K answer's code (0 armed), or kSealUnanswered when the Nano never answered.
  uint8_t sealCode() const { return sealCode_; }
  static constexpr uint8_t kSealUnanswered = 0xFF;
  // Starts the armed chain: its time 0 is 1000 µs after the G's newline reaches the Nano. (On the
  // board the step interrupt times the G; this sends it now.) False if the UART is full.
  bool startChain();
  // Dose records (protocol/nano.md "O"): asks O until the Nano answers O:0, once the link is free (in
  // a held pass too, after its G), and hands each record to the sink as it comes. A Nano that does not
  // answer is not counted as missing for it: the records are given up (doseDrained()).
  // Without a sink, the records are asked and dropped.
  void requestDose() { doseWanted_ = true; }
  // Every record asked for has come (or was given up): the last O answered O:0.
  bool doseDrained() const { return !doseWanted_ && inFlight_ != 'O'; }
  // Asks Q: the Nano's free buffers, armed programs and the last chain's state (uv::PassState).
  void requestPass() {
    passWanted_ = true;
    passAnswered_ = false;
  }
  bool passAnswered() const { return passAnswered_; }
  // Asks nothing but a requested Q while held: a scan pass's G must find the UART idle when its step
  // comes, and a pass loading its chain must hear of a free buffer at once, not after a T's reply.
  void hold(bool quiet) {
    held_ = quiet;
    if (!quiet) doseHeld_ = false;
  }
  // No O while held so (an O under way still ends), until released or hold(false): a scan program
  // loading, whose lines and K must follow the Q's answer at once (the relay). The O asked
  // meanwhile goes once released.
  void holdDose(bool held) { doseHeld_ = held; }
  uint8_t passFree() const { return passFree_; }
  uint8_t passArmed() const { return passArmed_; }
  uint8_t passState() const { return passState_; }

  // The Nano's clock against this one's (nano_clock.h), measured by W in the background; forgotten
  // when the Nano restarts or falls silent.
  const NanoClock& nanoClock() const { return clock_; }
  bool online() const { return online_; }
  // Whether to raise the link to kNanoFastBaud when idle (the board does; a test may not).
  void raiseSpeed(bool on) { raise_ = on; }
  // The link's speed now: 115200, or kNanoFastBaud once raised (or while the raise is being proved).
  uint32_t baud() const { return speed_ == Speed::Probing || speed_ == Speed::Raised ? kNanoFastBaud : uv::kNanoBaud; }
  // Raised and proved both ways.
  bool raised() const { return speed_ == Speed::Raised; }
  // The speed a job planned now runs at: kNanoFastBaud when raised or about to be (raising on, and
  // the last raise did not fail), else 115200: a Nano that never takes L (older firmware, or a wiring
  // that fails at the raised speed) runs its jobs at 115200.
  uint32_t jobBaud() const { return raised() || (raise_ && !raiseFailed_) ? kNanoFastBaud : uv::kNanoBaud; }
  // The last L went unanswered or refused, or its V at the new speed never came back (until a raise holds).
  bool raiseFailed() const { return raiseFailed_; }
  // Between the L and a proved speed, and while lowering, nothing but the link's own L, V and R goes.
  bool switching() const { return speed_ != Speed::Start && speed_ != Speed::Raised; }
  bool tempsKnown() const { return tempsKnown_; }
  // Since this start no temperature has come yet, and the Nano is not yet given up: the first
  // reading is on its way (M105 waits for it rather than answer E30 to a host that asks at once).
  bool firstReadingDue() const { return !tempsKnown_ && misses_ < kNanoMissesOffline; }
  const int16_t* deciC() const { return deciC_; }
  // The active fault bits of the last E (OVERTEMP, SENSOR).
  uint8_t activeFaults() const { return static_cast<uint8_t>(flags_ & uv::fault::kActive); }
  const char* firmware() const { return firmware_; }
  uint8_t takeEvents() {
    uint8_t e = events_;
    events_ = 0;
    return e;
  }
  // Sent lines, for the tests' accounting.
  uint32_t sent() const { return sent_; }

 private:
  // The line's bytes, or 0 if it did not go (the UART full).
  uint8_t send(const uv::NanoCommand& c);
  bool ask(char op, uint32_t nowUs);
  // A line that asks `op` went out: its reply is awaited, up to kNanoReplyTimeoutUs from now.
  void awaitReply(char op, uint32_t nowUs);
  void handle(const uv::NanoReply& r, uint32_t nowUs, DoseSink dose);
  // A requested O may go now.
  bool doseMayAsk(DoseSink dose) const { return doseWanted_ && !doseHeld_ && (!dose.take || dose.take(dose.ctx, nullptr)); }
  void missed(uint32_t nowUs);
  void fireFailed(uint8_t code);
  void flagsSeen(uint8_t flags, uint32_t nowUs);
  // A Nano that restarted or fell silent: its clock is measured again, from soon.
  void forgetClock(uint32_t nowUs);
  // Any doubt about the speed: back to 115200 once nothing is going out, raised again from retryAtUs.
  void lowerSpeed(uint32_t retryAtUs);
  bool speedStep(uint32_t nowUs);  // the raise's next step; true when it sent something

  ByteStream& io_;
  // The longest reply, O:, is 62 bytes at its widest (uv::kNanoReplyMax); a longer line is noise.
  static constexpr uint8_t kReplyMax = uv::kNanoReplyMax - 2;
  char line_[kReplyMax + 2];
  uv::LineSplitter splitter_;
  char inFlight_ = 0;        // the op whose reply we wait for, or 0
  uint32_t askedAt_ = 0;
  uint8_t misses_ = 0;
  uint32_t nextThermal_ = 0, nextFault_ = 0;
  uint16_t boot_ = 0;
  uint32_t fires_ = 0;
  int16_t deciC_[uv::kSensorCount] = {};
  uint8_t flags_ = 0;
  char firmware_[12] = {};  // e.g. 0.1.0: a longer one is cut
  FireState fire_ = FireState::Idle;
  uint8_t fireError_ = 0, fireFlags_ = 0;
  uint32_t fireEndsAt_ = 0, nextStatus_ = 0;
  uint8_t events_ = 0;
  uint32_t sent_ = 0;
  uint8_t sealCode_ = 0, passFree_ = 0, passArmed_ = 0, passState_ = 0;
  NanoClock clock_;
  uint32_t nextClock_ = 0, clockSentUs_ = 0;  // the next W; this clock's micros() as the last went out
  // Start: 115200; Asked: L sent at 115200; Probing: both changed, V sent at the new speed; Raised:
  // proved; Lowering: back to 115200 as soon as the transmitter is idle; Waking: begin()'s 0x00 sent,
  // the R to follow.
  enum class Speed : uint8_t { Start, Asked, Probing, Raised, Lowering, Waking };
  Speed speed_ = Speed::Start;
  // The flags, a bit each (the Mega's static RAM is short: docs/firmware-mega.md "Static RAM"); set
  // in the constructor, as C++11 gives a bit-field no initializer.
  bool online_ : 1;
  bool reportedOffline_ : 1;
  bool offPending_ : 1;  // an R that found the UART full
  bool identityWanted_ : 1;
  bool probeWanted_ : 1, probeAnswered_ : 1, probeTriggered_ : 1;
  bool countersWanted_ : 1, countersAnswered_ : 1, whole_ : 1;
  bool tempsKnown_ : 1;
  bool fireCheckWanted_ : 1;  // S said off: ask E once
  bool sealAnswered_ : 1, passWanted_ : 1, passAnswered_ : 1, held_ : 1, doseHeld_ : 1;
  bool raise_ : 1;
  bool raiseSoon_ : 1;
  bool raiseFailed_ : 1;  // the last raise failed (its L or its V): jobs are planned at 115200
  bool doseWanted_ : 1;   // a record waits to be asked for with O
  uint32_t nextSpeed_ = 0;  // when an L may next go
};

}  // namespace mega
