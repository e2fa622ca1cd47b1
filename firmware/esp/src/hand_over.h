// What the ESP's network task and loop() say to each other about HTTP requests, and the rings that
// carry it. Each side owns its own things and only messages cross: the network task owns every
// request (the library's objects are made, answered and freed there) and the spooled body while
// it arrives; loop() owns the Mega's link (the bridge, the print intake) and the spool while it
// checks and uploads it. A request crosses as a ticket, never as a pointer. Every ring is fixed
// and nothing waits on one: full, the network task answers 503 and loop() tries again next pass.
//
//   network task                    work (16)                       loop()
//   NetworkDesk (network_desk.h)  ------------>  Status, Cancel, CheckBody, Left   LoopDesk (loop_desk.h)
//                                 <------------  answers (2): ticket, status, body
//                                 <------------  notes (4): the Mega's admission, the spool back
#pragma once
#include <stdint.h>

#include "bridge.h"
#include "spsc_ring.h"

namespace uv {
namespace esp {

enum class Ask : uint8_t {
  Status,     // GET /status
  Cancel,     // DELETE /print
  CheckBody,  // a POST /print whose body is whole on the spool, which goes to loop() with it
  Left,       // the client of the CheckBody of this ticket has gone: its job must not start
};

struct Work {
  uint16_t ticket;  // names the request on the network task; never 0
  Ask ask;
  bool spoolFailed;  // CheckBody: the body could not be stored whole
};

constexpr uint16_t kAnswerBytes = 2048;  // a status snapshot, or any error (kErrorJsonBytes)

struct Answer {
  uint16_t ticket;
  uint16_t status;
  bool plainText;  // the JSON did not fit: a short text instead, never cut-off JSON
  char body[kAnswerBytes];
};

// What the network task needs of loop()'s state to judge a POST before keeping its body.
struct HubNote {
  Admission admission;  // what Bridge::printAdmission says now
  bool spoolBack;       // loop() has let go of the spool: another body may be stored
};

struct HandOver {
  static constexpr uint8_t kWaiting = 8;  // requests waiting for loop() (protocol/esp.md "overloaded")
  // The kWaiting requests and a check's Left, with room to spare for the entries of requests whose
  // clients left before loop() took them; full all the same, a request is answered 503.
  SpscRing<Work, 16> work;
  // Two: a DELETE during a check answers both at once. More would only cost RAM: loop() keeps a
  // request whose answer has no room in `work` until the network task has sent the earlier ones.
  SpscRing<Answer, 2> answers;
  SpscRing<HubNote, 4> notes;
};

}  // namespace esp
}  // namespace uv
