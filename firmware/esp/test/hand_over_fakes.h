// Stand-ins for the hand-over's tests (hand_over_test.cpp, hand_over_race_test.cpp): a request as
// the library holds it (a shared_ptr that its client's leaving ends), the spool both tasks touch
// in turn, the bridge's admission and upload, and a print intake that checks the spool in steps.
// None of them locks anything: whatever the two test threads share must be handed over, or the
// ThreadSanitizer build reports the race.
#pragma once
#include <stdint.h>

#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "loop_desk.h"
#include "network_desk.h"

namespace handover {

using uv::esp::Admission;
using uv::esp::Answer;
using uv::esp::Ask;
using uv::esp::Intake;
using uv::esp::JsonWriter;

// An HTTP request on the network task: answered at most once, and only there.
struct Request {
  std::thread::id owner = std::this_thread::get_id();
  int sends = 0;
  uint16_t status = 0;
  std::string body;
};
using Handle = std::weak_ptr<Request>;

// The spooled body: written by the network task while it arrives, read by loop() while it checks.
struct Spool {
  std::string text;
};

struct Hub {
  const Spool& spool;  // the upload makes the job's records from the body as it sends them
  Admission mega = Admission::Accepted;  // online and idle, or offline, or running a job
  bool reserved = false;
  int uploadPasses = 0;  // passes the running upload still takes
  int uploadsStarted = 0;
  size_t bytesSent = 0;
  Admission printAdmission(uint32_t) const {
    if (reserved || uploadPasses) return Admission::Busy;
    return mega;
  }
  Admission admitPrint(uint32_t nowMs) {
    Admission a = printAdmission(nowMs);
    reserved = a == Admission::Accepted;
    return a;
  }
  bool cancel() {
    bool any = uploadPasses > 0;
    uploadPasses = 0;
    return any;
  }
  bool uploading() const { return uploadPasses > 0; }
  void writeStatus(JsonWriter& w, uint32_t nowMs) const {
    w.beginObject().key("mega").string(mega == Admission::MegaOffline ? "offline" : "online").key("ms").number(nowMs).endObject();
  }
  void poll() {
    if (!uploadPasses) return;
    bytesSent += spool.text.size();
    uploadPasses--;
  }
};

// The print intake: `steps` passes to read the spool, then 202 (the upload starts) or 400 for a
// body that says "bad".
struct Check {
  Hub& hub;
  Spool& spool;
  int steps = 3;
  int left = 0;
  bool busy_ = false, bodyOpen = false;
  uint16_t status_ = 0;
  std::string response_;
  size_t bytesRead = 0;

  void begin() {
    busy_ = bodyOpen = true;
    left = steps;
  }
  bool busy() const { return busy_; }
  // The ESP8266's flash yields inside loop()'s reads of the spool, to the network callbacks.
  std::function<void()> yield;

  template <class NextId>
  Intake step(NextId nextId) {
    if (yield) yield();
    bytesRead += spool.text.size();  // loop() reads the body here: the network task must not write it
    if (--left > 0) return Intake::Working;
    busy_ = false;
    hub.reserved = false;
    if (spool.text.find("bad") != std::string::npos) return verdict(400, R"({"error":{"code":"bad_json"}})", Intake::Refused);
    hub.uploadPasses = 5;
    hub.uploadsStarted++;
    return verdict(202, R"({"job":{"id":)" + std::to_string(nextId()) + "}}", Intake::Accepted);
  }
  void cancel() {
    busy_ = false;
    hub.reserved = false;
    verdict(409, R"({"error":{"code":"cancelled"}})", Intake::Refused);
  }
  void closeBody() { bodyOpen = false; }
  uint16_t status() const { return status_; }
  const char* response() const { return response_.c_str(); }

 private:
  Intake verdict(uint16_t status, const std::string& text, Intake r) {
    status_ = status;
    response_ = text;
    return r;
  }
};

using Network = uv::esp::NetworkDesk<Handle>;
using Loop = uv::esp::LoopDesk<Hub, Check>;

// Both sides of the hand-over, wired as on the ESP: the rings between them, the network task's
// desk, and loop()'s desk with the hub, the print check and the spool they share.
struct Desks {
  uv::esp::HandOver rings;
  Spool spool;
  Hub hub{spool};
  Check check{hub, spool};
  Network network{rings};
  Loop loop{rings, hub, check};
};

// One thread playing both sides in turn: the network task's part of a request (handed, answered by
// its client's poll) and loop()'s passes, as hand_over_test and hand_over_yield_test drive them.
struct Rig : Desks {
  uint32_t ids = 0, ms = 0;

  // The network task's whole side of one request: paused, handed, its client's poll pumping.
  std::shared_ptr<Request> ask(Ask a, uint16_t& ticket) {
    auto r = std::make_shared<Request>();
    ticket = network.hand(r, a);
    return r;
  }
  // A POST whose headers passed: its body is stored, then handed with the spool.
  std::shared_ptr<Request> post(const std::string& body, uint16_t& ticket) {
    if (network.admitBody() != Admission::Accepted) return nullptr;
    spool.text = body;
    auto r = std::make_shared<Request>();
    ticket = network.hand(r, Ask::CheckBody);
    return r;
  }
  void pump() {
    network.pump([](Request& r, const Answer& a) {
      r.sends++;
      r.status = a.status;
      r.body = a.body;
    });
  }
  void pass() {
    loop.poll(ms += 10, [this] { return ++ids; });
    hub.poll();
  }
  // Both sides until nothing moves: every answer out, the upload over, the spool back.
  void settle() {
    for (int i = 0; i < 50; i++) {
      pass();
      pump();
    }
  }
};

}  // namespace handover
