// The Mega's command core (protocol/mega.md §5): takes accepted lines from both host ports in turn,
// runs each command (long ones as state machines polled by the main loop, so nothing ever waits),
// keeps the reports and the safety rules. Plain C++: the hardware sits behind its collaborators.
#pragma once
#include <stdint.h>

#include "config.h"
#include "config_store.h"
#include "dialect_command.h"
#include "dialect_reply.h"
#include "gcode_file.h"
#include "host_link.h"
#include "homing.h"
#include "job_plan.h"
#include "job_runner.h"
#include "job_spool.h"
#include "stream_job.h"
#include "buttons.h"
#include "machine_io.h"
#include "mesh_store.h"
#include "probe.h"
#include "screen.h"
#include "motion.h"
#include "printhead_link.h"
#include "selftest.h"

namespace mega {

constexpr uint32_t kKeepaliveUs = 2000000;  // busy: every 2 s during a long command, unless M113 says otherwise
constexpr uint8_t kKeepaliveMaxS = 60;      // M113's range, as Marlin's
constexpr uint8_t kPorts = 2;               // USB, ESP

// What the main loop measures about itself, for M821 (the never-blocks check).
struct LoopStats {
  uint32_t loopMaxUs;      // the longest main-loop pass
  uint16_t stepIsrMaxUs;   // the longest step interrupt
};

constexpr uint16_t larger(uint16_t a, uint16_t b) { return a > b ? a : b; }

// The P of M24, M828 and M1000 (mega.md "Pacing"): P1 paces the job, P0 does not; anything else is E11.
// A JOB: line's buffer. Its longest: `JOB:running` (11), a 31-character file (37), stop= with two
// 10-digit counts (27), elapsed= and remaining= at their 7-digit cap (16 + 18), leds= (7), the longest
// reason= (17) and paced= (8): 141 and the NUL. mode=stream comes only with the 6-letter file
// `stream`, and cooling=1 only while running (no reason). A line must fit kTxRing - 1 whole.
constexpr uint8_t kJobLineMax = 142;
static_assert(kJobLineMax <= kTxRing - 1, "a JOB: line must fit the transmit ring");

enum class Pace : uint8_t { Unsaid, Off, On, Bad };
inline Pace paceOf(const uv::Command& c) {
  if (!c.has('P')) return Pace::Unsaid;
  if (!c.hasValue('P')) return Pace::Bad;
  return c.value('P') == 0 ? Pace::Off : c.value('P') == 1000 ? Pace::On : Pace::Bad;
}

struct MachineParts {
  HostLink* ports[kPorts];
  Motion& motion;
  PrintheadLink& head;
  Config& config;
  ConfigStore& store;
  Storage& sd;
  MachineIo& io;
  Eeprom& eeprom;
  TextDisplay& display;
  const char* firmwareName;  // in flash (UV_FLASH)
  uint8_t& movesFree;  // the P of every ok, which the ports read
  LoopStats& stats;
};

class Machine {
 public:
  explicit Machine(const MachineParts& p);

  // After power-up: the config, `start` on both ports, LEDs off.
  void begin(uint32_t nowUs);
  // One pass of the main loop's work. Never waits.
  void poll(uint32_t nowUs);
  // M112, the e-stop button: LEDs off, motion stopped, job aborted, halted until M999.
  void emergency();

  bool halted() const { return halted_; }
  // A job from the card is exposing now (not paused): what a machine with no host listening runs on
  // with, and whether it was started paced. The simulated printer keeps a page's reload by them.
  bool cardJobRunning() const { return arena_ == Arena::Run && run()->state() == RunState::Running; }
  bool jobPaced() const { return running() && run()->paced(); }
  bool leveling() const { return leveling_; }
  int16_t meshPoint(uint8_t i, uint8_t j) { return mesh_.z(i, j); }
  uint8_t homed() const { return homed_; }

  // When a command may run beyond its turn (the command table, machine_commands.cpp): kQuery while
  // another port's long command is under way, kStream between a running stream's records,
  // kWhileHalted after M112 until M999.
  enum CommandFlag : uint8_t { kQuery = 1, kStream = 2, kWhileHalted = 4 };
  // The table's flags for a command; 0 for one not in it.
  static uint8_t commandFlags(const uv::Command& c);
  // Whether the command table has a row for it (a command answered E10 has none).
  static bool knows(const uv::Command& c);

 private:
  enum class Result : uint8_t { Done, Long, Wait };
  using Handler = Result (Machine::*)(HostLink& port, const uv::Command& c);
  // One command: its letter and code, its CommandFlags, and the member that runs it. A new command
  // is a row of kCommands (and its line in protocol/mega.md).
  struct CommandRow {
    char letter;
    uint16_t code;
    uint8_t flags;
    Handler run;
  };
  static const CommandRow kCommands[];
  // The row of a command, copied out of flash into `row`; false if it has none.
  static bool findCommand(const uv::Command& c, CommandRow& row);
  // Answer: the command has ended, and its reply waits for room on its port (finishLong).
  enum class Op : uint8_t { None, Emit, Dwell, Home, SelfTest, Servo, ProbeRead, MoveRoom, Release, Plan, Prepare, Probe, Level, Store, Answer };
  enum class Gen : uint8_t { Firmware, Endstops, Config, Files, Mesh };
  // What the job arena holds: an upload, a planning, a preparation from a job copied onto the card, a run.
  enum class Arena : uint8_t { Empty, Spool, Plan, Run, Stream, Gcode };
  // A stream's planner and its runner, together in the arena.
  struct StreamArena {
    StreamJob job;
    JobRunner runner;
  };

  Result execute(HostLink& port, const LineSlot& line);
  // Runs a command from the table, or answers E10 for one not in it (machine_commands.cpp).
  Result dispatch(HostLink& port, const uv::Command& c);
  // Commands of the core (machine_commands.cpp).
  Result firmwareInfo(HostLink& port, const uv::Command& c);   // M115
  Result reportPeriod(HostLink& port, const uv::Command& c);   // M154, M155
  Result refuseM110(HostLink& port, const uv::Command& c);     // M110
  Result nothing(HostLink& port, const uv::Command& c);        // M108, M112
  Result cardInit(HostLink& port, const uv::Command& c);       // M21
  Result leaveHalt(HostLink& port, const uv::Command& c);      // M999
  void runLong();
  void finishLong(uint8_t error = 0, const char* detail = nullptr);
  bool emitNext();
  void reports();
  void printheadEvents();
  void sayHeadFaults();
  void broadcast(const char* text);
  void broadcastP(const char* text);  // a line in flash (UV_P)
  // A dose record from the printhead (PrintheadLink's sink): the job's DOSE: line to every host. With
  // nullptr: whether every host has room for such a line now.
  static bool doseRecord(void* self, const uv::NanoReply* record);

  // commands (machine_motion.cpp)
  Result move(HostLink& port, const uv::Command& c);
  Result home(HostLink& port, const uv::Command& c);
  Result jog(HostLink& port, const uv::Command& c);
  Result selfTest(HostLink& port, const uv::Command& c);
  Result dwell(HostLink& port, const uv::Command& c);
  // M400: waits for every queued move to end (a dwell of nothing after the queue).
  Result drain(HostLink& port, const uv::Command& c);
  // M113: the busy: interval of this port.
  Result busyInterval(HostLink& port, const uv::Command& c);
  // The busy: interval of a port (M113), µs; 0: none.
  uint32_t keepaliveUs(const HostLink* port) const;
  Result release(HostLink& port, const uv::Command& c);
  Result absoluteMode(HostLink& port, const uv::Command& c);  // G90
  Result relativeMode(HostLink& port, const uv::Command& c);  // G91
  Result motorsOn(HostLink& port, const uv::Command& c);      // M17
  Result quickStop(HostLink& port, const uv::Command& c);     // M410
  Result position(HostLink& port, const uv::Command& c);      // M114
  bool axisHomed(uint8_t axis) const { return homed_ & (1 << axis); }
  // commands (machine_printhead.cpp)
  Result temperatures(HostLink& port, const uv::Command& c);
  Result servo(HostLink& port, const uv::Command& c, char op);
  Result deployProbe(HostLink& port, const uv::Command& c);  // M401
  Result stowProbe(HostLink& port, const uv::Command& c);    // M402
  Result servoAngle(HostLink& port, const uv::Command& c);   // M280
  Result endstops(HostLink& port, const uv::Command& c);     // M119
  Result light(HostLink& port, const uv::Command& c);
  Result diagnostics(HostLink& port, const uv::Command& c);
  // commands (machine_job.cpp)
  Result jobCommand(HostLink& port, const uv::Command& c);
  Result uploadRecord(HostLink& port, const LineSlot& line);
  Result endUpload(HostLink& port);
  // M28 and M23 need a card and no job under way; false, or the refusal said.
  bool refuseCardJob(HostLink& port);
  Result select(HostLink& port, const uv::Command& c);
  // M24, M828 and M1000's P: its value, or Pace::Bad once E11 has been answered.
  Pace paceParam(HostLink& port, const uv::Command& c);
  Result startOrContinue(HostLink& port, const uv::Command& c);
  Result resumeInterrupted(HostLink& port, const uv::Command& c);
  uint8_t startPlanning(const uv::JobHeader& header);
  void planRefused(HostLink& port, uint8_t err);
  void runJob();
  void resumeVerdict(JobRunner& j);
  // Prints a line on both hosts if both have room for it now; false (nothing printed) if not.
  bool broadcastWhole(const char* text);
  void clearArena();
  // The JOB: line into `out`, kJobLineMax bytes: the longest fits a host's transmit ring whole.
  uint8_t formatJob(char* out) const;
  void jobReports();
  // What keeps a job from exposing now (the printhead silent, a sensor broken, the head hot, an axis
  // not homed): the error said on `port` and its code, or 0. `heatWaits`: heat is no refusal (a paced
  // continue waits it out).
  uint8_t refuseExposure(HostLink& port, bool heatWaits = false);
  Result startStream(HostLink& port, const uv::Command& c);
  Result streamLine(HostLink& port, const LineSlot& line);
  // G-code files on the card (machine_card_gcode.cpp): true if the command was one of theirs.
  bool gcodeCommand(HostLink& port, const uv::Command& c, Result& r);
  void saySelected(HostLink& port, const char* name, uint8_t len, uint32_t size);
  Result storeGcodeLine(HostLink& port, const LineSlot& line);
  // Runs the selected G-code file's next line when no host line ran this pass.
  void runCardLine();
  void stopCardFile();
  // Marlin's `SD printing byte <pos>/<size>` while a G-code file is selected; false if none is.
  bool formatCardProgress(char* out);
  // the panel (machine_panel.cpp)
  void panel();
  void button(uint8_t pressed);
  // The snapshot row `row` shows; the costly fields (positions, time left: 64-bit divisions, about
  // 125 us each on the AVR) only for the rows that show them.
  ScreenState screenState(uint8_t row) const;
  Result message(HostLink& port, const uv::Command& c);
  // commands (machine_probe.cpp)
  // G30 and G29 need every axis homed and the probe out; false, or the refusal said.
  bool refuseProbing(HostLink& port);
  Result probeOnce(HostLink& port, const uv::Command& c);
  Result level(HostLink& port, const uv::Command& c);
  Result meshCommand(HostLink& port, const uv::Command& c);
  void runProbe();
  void runLevel();
  bool emitMesh(char* buf);
  void writeMeshFile();
  uint8_t formatPoint(char* out, int32_t x, int32_t y, int32_t z) const;
  // commands (machine_config.cpp)
  Result configCommand(HostLink& port, const uv::Command& c);
  // Settings that act at once: the position report period, the direction pins.
  void applyConfig();
  // A changed steps/mm makes the step count mean another place: that axis must home again.
  void stepsChanged(const int32_t before[3]);

  bool jobActive() const {
    if (arena_ == Arena::Spool && !preparing_) return true;
    if (arena_ == Arena::Stream) return streaming_ || runLive();
    if (arena_ == Arena::Gcode) return gcode()->uploading() || gcode()->running;
    return arena_ == Arena::Run && runLive();
  }
  bool runLive() const { return run()->state() == RunState::Running || run()->state() == RunState::Paused; }
  JobSpool* spool() { return reinterpret_cast<JobSpool*>(arenaMem_); }
  JobPlan* plan() { return reinterpret_cast<JobPlan*>(arenaMem_); }
  // The runner, of a job on the card or of a stream.
  JobRunner* run() { return arena_ == Arena::Stream ? &stream()->runner : reinterpret_cast<JobRunner*>(arenaMem_); }
  const JobRunner* run() const { return const_cast<Machine*>(this)->run(); }
  StreamArena* stream() { return reinterpret_cast<StreamArena*>(arenaMem_); }
  GcodeFile* gcode() { return reinterpret_cast<GcodeFile*>(arenaMem_); }
  const GcodeFile* gcode() const { return reinterpret_cast<const GcodeFile*>(arenaMem_); }
  bool running() const { return (arena_ == Arena::Run || arena_ == Arena::Stream); }
  uint8_t formatTemps(char* out) const;
  uint8_t formatPosition(char* out) const;

  HostLink* ports_[kPorts];
  Motion& motion_;
  PrintheadLink& head_;
  Config& config_;
  ConfigStore& store_;
  Storage& sd_;
  MachineIo& io_;
  Homing homing_;
  SelfTest test_;
  Probe probe_;
  MeshStore mesh_;
  Screen screen_;
  Buttons buttons_;
  char message_[kScreenCols + 1] = {};
  uint8_t lastFault_ = 0;
  // The printhead's FAULT lines still owed to each port: bit (kind << port).
  struct HeadFaults {
    static constexpr uint8_t kOffline = 1, kThermal = 1 << kPorts;  // kinds, each with a bit per port
    uint8_t owed;
    bool sensor;  // the thermal fault is a sensor's, not a temperature over its limit
    uint8_t hot;
    int16_t deciC;
  } headFaults_ = {};
  static constexpr uint8_t kAllPorts = (1 << kPorts) - 1;
  const char* firmwareName_;

  uint32_t now_ = 0;
  // G0/G1's feed rate, µm/s: modal, as Marlin's, shared by G0 and G1 and by both ports, until the next F.
  // 0 until one is given (start-up, M112): the configured travel speed.
  uint32_t feedUmS_ = 0;
  uint8_t& movesFree_;
  LoopStats& stats_;
  uint8_t next_ = 0;  // the port whose line runs next (round robin)
  uint8_t keepaliveS_[kPorts] = {kKeepaliveUs / 1000000, kKeepaliveUs / 1000000};  // M113, per port
  uint8_t homed_ = 0;
  bool halted_ = false;
  bool absolute_ = true;
  bool lightOn_ = false;
  bool deployed_ = false;  // the CR Touch's pin is out (M401 answered PROBE:deployed)
  bool leveling_ = false;  // exposures follow the mesh (M420 S1, or after G29)

  struct Long {
    Op op;
    HostLink* port;
    uint32_t since, until, keepalive;
    Gen gen;
    uint8_t index;
    uint16_t fileIndex;
    uint8_t meshK;  // G29: the point being probed, in serpentine order
    bool moving;    // G29: on the way to that point
    bool drain;     // G4, M400, G28, M18/M84: the queued moves end before the command's own work starts (Marlin)
    bool fromCard;  // a line of a G-code file: it has no ok to send
    char servoOp;
    union {  // one command's state at a time: the two share their bytes
      struct {
        int32_t target[3];
        uint32_t feed;
      };                // MoveRoom, jog
      char detail[16];  // Answer: the error's detail, kept until there is room to say it
    };
    uint8_t error;      // Answer: the error to say, 0 for none
  } long_ = {};

  // The job: one arena for whichever stage is live, so the planner's memory is there only while
  // it plans (job_plan.h).
  // A job on the card runs with its runner at the arena's start and, for a scan job, the planner
  // of its passes after it (JobRunner::setScanMemory).
  static constexpr uint16_t kArenaAlign = alignof(CardScan) > 4 ? alignof(CardScan) : 4;
  static constexpr uint16_t kRunnerBytes = (sizeof(JobRunner) + kArenaAlign - 1) & ~(kArenaAlign - 1u);
  static constexpr uint16_t kArenaBytes =
      larger(larger(larger(sizeof(JobSpool), sizeof(JobPlan)), larger(kRunnerBytes + sizeof(CardScan), sizeof(StreamArena))), sizeof(GcodeFile));
  JobRunner* newRunner();
  alignas(kArenaAlign) uint8_t arenaMem_[kArenaBytes];
  Arena arena_ = Arena::Empty;
  const HostLink* jobPort_ = nullptr;  // the port whose records an upload or a stream takes
  uv::JobState jobState_ = uv::JobState::Idle;  // when no run is live
  char selected_[kFileNameMax + 1] = {};
  bool preparing_ = false;  // the spool builds a PC-copied job's working files (M23)
  bool preparedSelect_ = false;  // the planning under way was started by M23, not M29
  bool streaming_ = false;       // M828's records are still coming (until M29)
  uint32_t streamBusyAt_ = 0;    // a record waits for room: when the next busy: goes out
  bool streamWaiting_ = false;
  bool faultToShow_ = false;  // a job's FAULT line waits for room on the hosts
  uint32_t jobPeriodUs_ = 0, jobNext_ = 0;
  uint32_t lastHeardUs_ = 0;

  uint32_t tempPeriodUs_ = 0, tempNext_ = 0;
  uint32_t posPeriodUs_ = 0, posNext_ = 0;
};

}  // namespace mega
