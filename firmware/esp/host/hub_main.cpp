// The ESP's hub run on the host: the same core (bridge, print intake, live channel, HTTP rules,
// Wi-Fi settings, and the hand-over between the network's side and loop()'s, as the ESP8266 runs
// it: one thread, the network's turn between loop()'s passes) behind a real HTTP and WebSocket
// server (Boost.Beast), in front of the whole
// simulated Mega of the Mega's host tests (its command core with the real Nano logic). The
// end-to-end tests drive the app against it in Chromium, with the app served the way the ESP
// serves it: gzipped files from the flash image (`npm run build:esp`), with ETags.
//
//   esp_host [--port N] [--www DIR] [--speed X] [--board esp8266|esp32] [--turn each-pass|poll|wake]
//            [--request-deadline-ms N]    prints "listening on http://127.0.0.1:PORT"
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <unistd.h>

#include "flash_gate.h"
#include "heap_count.h"
#include "host_body.h"
#include "host_flash.h"
#include "http_rules.h"
#include "http_sessions.h"
#include "lifeline.h"
#include "board.h"
#include "live_sessions.h"
#include "loop_desk.h"
#include "mega_rig.h"
#include "network_desk.h"
#include "print_intake.h"
#include "wifi_settings.h"

namespace net = boost::asio;
using tcp = net::ip::tcp;
using namespace uv::esp;

namespace {

// The hub's HTTP answer; uv::esp::Answer is loop()'s, in the hand-over's rings.
using Answer = hub::Answer;

mega::MegaRig* rigPtr = nullptr;
uint32_t virtualMs() { return static_cast<uint32_t>(rigPtr->nowUs / 1000); }

// The Mega's UART: bytes go straight into the simulated Mega's receive side.
struct RigWire : MegaWire {
  mega::MegaRig& rig;
  explicit RigWire(mega::MegaRig& r) : rig(r) {}
  bool write(const char* data, uint16_t n) override {
    rig.esp.toMega.append(data, n);
    return true;
  }
};

std::string readFile(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

Answer error(unsigned status, const char* code, const char* message, const char* path = "") {
  char buf[kErrorJsonBytes];
  JsonWriter w(buf, sizeof buf);
  writeError(w, code, message, path);
  return {status, "application/json", w.text(), {}};
}

Method methodOf(hub::http::verb v) {
  switch (v) {
    case hub::http::verb::get:
    case hub::http::verb::head: return Method::Get;
    case hub::http::verb::post: return Method::Post;
    case hub::http::verb::delete_: return Method::Delete;
    default: return Method::Other;
  }
}

// A request waiting for loop(): the session's way to answer it. The desk's handle on it; on the
// host it is held, not weak, since a Beast session that waits reads nothing and so never learns
// that its client left (a POST whose body is cut short is still seen: Routes::lost).
using Later = std::function<void(Answer)>;
struct LaterHandle {
  std::shared_ptr<Later> later;
  std::shared_ptr<Later> lock() const { return later; }
  bool expired() const { return !later; }
};

class Hub : public hub::Routes {
 public:
  Hub(net::io_context& io, std::filesystem::path www, std::filesystem::path state, const Board& board)
      : io_(io), www_(std::move(www)), state_(std::move(state)), sessions_(board), body_((state_ / "job.json").string(), &flash_, &gate_) {
    rigPtr = &rig_;
    // The ESP8266's flash yields inside loop()'s file operations, and the yield runs the network
    // callbacks that are ready (host_flash.h): here, the io_context's handlers.
    flash_.yield = [this] { io_.poll(); };
    sessions_.attach(bridge_, live_, virtualMs);
    defaultWifi(0x5EED01, [] { return static_cast<uint32_t>(std::random_device{}()); }, wifi_);
  }

  void begin() {
    hub::heap::RigScope rig;  // the simulated Mega's memory is not the hub's
    rig_.begin();
    char panel[17];
    panelLine(wifi_, panel);
    bridge_.begin(virtualMs(), panel);
  }

  // One real millisecond: `speed` of the Mega's, the hub's loop after each.
  void tick(double speed) {
    budget_ += speed;
    for (; budget_ >= 1; budget_ -= 1) {
      {
        hub::heap::RigScope rig;
        rig_.run(1000);
      }
      for (; fed_ < rig_.espLines.size(); fed_++)
        for (char c : rig_.espLines[fed_] + "\n") bridge_.received(c, virtualMs());
      // The rig keeps every line its hosts read; the hub has taken them (a long soak stays flat).
      rig_.espLines.clear();
      rig_.usbLines.clear();
      rig_.firedAt.clear();
      fed_ = 0;
      sessions_.drain();  // loop()'s side of /ws: who joined and left, and their messages
      bridge_.poll(virtualMs());
      loopDesk_.poll(virtualMs(), [this] { return ++jobs_; });
      passes.fetch_add(1, std::memory_order_relaxed);
      if (turn_ == Turn::EachPass) {
        networkTurn();  // as the ESP8266's loop() ends: its answers and live messages go out at once
      } else if (turn_ == Turn::Poll) {
        live_.pump();  // as the ESP32's loop() did before issue 36, on the wrong task; answers wait for the poll
      } else if (turn_ == Turn::Woken && !wakePending_ &&
                 (rings_.answers.room() < 2 || live_.written() != woken_ || (live_.backlogged() && virtualMs() - backlogMs_ >= 10))) {
        // As the ESP32's loop() (main.cpp, arduino/network_wake.cpp): the network task is woken to send.
        wakePending_ = true;
        woken_ = live_.written();
        if (live_.backlogged()) backlogMs_ = virtualMs();
        net::post(io_, [this] {
          wakePending_ = false;
          networkTurn();
        });
      }
      io_.poll();  // the network gets its turn every millisecond of the hub's time, as in the ESP's loop
      if (flash_.reentered()) {  // what corrupts LittleFS on the ESP8266: the gate was not asked
        std::fprintf(stderr, "esp_host: the flash was re-entered by a network callback inside a file operation of loop()'s\n");
        std::abort();
      }
    }
  }

  // When the network side sends what loop() published: after each pass (the ESP8266); the live
  // channel from loop() and the answers at AsyncTCP's poll of their connection every 500 ms (the
  // ESP32 before issue 36); or both at that poll and when loop() wakes the network task (the ESP32 now).
  enum class Turn { EachPass, Poll, Woken };
  void setTurn(Turn t) {
    turn_ = t;
    if (t != Turn::EachPass) poll();
  }
  static inline std::atomic<uint64_t> passes{0};

  // The network's side, as onBody on the ESP: a POST's headers are judged before a byte of its
  // body is kept, by what loop() last said of the Mega and the spool.
  bool beforeBody(const hub::http::request_parser<hub::http::string_body>& parser, uint32_t& body, Answer& now) override {
    const auto& req = parser.get();
    std::string path(req.target());
    if (path != "/print" || req.method() != hub::http::verb::post) return false;
    pump();
    auto ct = req.find(hub::http::field::content_type);
    std::string contentType = ct == req.end() ? "" : std::string(ct->value());
    bool hasLength = parser.content_length().has_value();
    uint32_t length = hasLength ? static_cast<uint32_t>(std::min<uint64_t>(*parser.content_length(), 0xffffffffu)) : 0;
    HttpError e = foreign(req);
    if (!e.status) e = printHeaderError(contentType.empty() ? nullptr : contentType.c_str(), hasLength, length);
    if (!e.status) e = admissionError(desk_.admitBody());
    if (!e.status) {  // the body is arriving: the spool is this request's
      body = desk_.arriving();
      return false;
    }
    now = error(e.status, e.code, e.message);
    return true;
  }

  bool handle(const hub::http::request<hub::http::string_body>& req, uint32_t body, Answer& now, std::function<void(Answer)> later) override {
    std::string path(req.target());
    std::string host(req[hub::http::field::host]);
    if (isForeignHost(host.c_str(), "192.168.4.1", "uvprinter") && host.rfind("127.0.0.1", 0) != 0 && host.rfind("localhost", 0) != 0) {
      now = {302, "", "", {{"Location", "http://192.168.4.1/"}}};
      return true;
    }
    HttpError m = methodNotAllowed(path.c_str(), methodOf(req.method()));
    if (m.status) return now = error(m.status, m.code, m.message), true;
    if (path == "/status") return handOver(Ask::Status, now, std::move(later));
    if (path == "/print" && req.method() == hub::http::verb::post) {
      if (desk_.bodyCancelled(body) || desk_.arriving() != body) return now = error(409, kCancelledCode, kCancelledMessage), true;  // a DELETE came first
      if (gate_.held()) {  // loop() is inside a file operation (flash_gate.h): nothing of the body is kept
        desk_.bodyAbandoned(body);
        return now = flashBusy(), true;
      }
      flash_.callbackOperation([&] { return static_cast<bool>(std::ofstream(body_.path(), std::ios::binary) << req.body()); });  // onBody's writes
      return handOver(Ask::CheckBody, now, std::move(later));
    }
    if (req.method() == hub::http::verb::post || req.method() == hub::http::verb::delete_) {
      HttpError e = foreign(req);
      if (!e.status && req.method() == hub::http::verb::post) e = jsonBodyError(contentTypeOf(req).c_str());
      if (e.status) return now = error(e.status, e.code, e.message), true;
    }
    if (path == "/print" && desk_.cancelArriving()) return now = {200, "application/json", kCancelledJson, {}}, true;  // DELETE, a body arriving
    if (path == "/print") return handOver(Ask::Cancel, now, std::move(later));  // DELETE
    if (path == "/wifi") return now = wifi(req), true;
    now = appFile(req, path);
    return true;
  }

  // As the ESP's onDisconnect: a POST /print body cut short frees the spool.
  void lost(const hub::http::request_parser<hub::http::string_body>&, uint32_t body) override {
    if (body) desk_.bodyAbandoned(body);
  }

  // /ws drives the Mega: only the hub's own pages may open it.
  bool refuseUpgrade(const hub::http::request<hub::http::string_body>& req, Answer& now) override {
    HttpError e = foreign(req);
    if (e.status) now = error(e.status, e.code, e.message);
    return e.status != 0;
  }

  void upgrade(boost::beast::tcp_stream&& stream, hub::http::request<hub::http::string_body> req, hub::SocketSlot slot) override {
    if (req.target() != "/ws") return;
    std::make_shared<hub::WsSession>(std::move(stream), sessions_, std::move(slot))->start(std::move(req));
  }

 private:
  // The Origin rule (http_rules.h originError), as the ESP applies it.
  static HttpError foreign(const hub::http::request<hub::http::string_body>& req) {
    auto o = req.find(hub::http::field::origin);
    std::string origin = o == req.end() ? "" : std::string(o->value());
    std::string host(req[hub::http::field::host]);
    return originError(origin.c_str(), host.c_str(), "192.168.4.1", "uvprinter");
  }
  static std::string contentTypeOf(const hub::http::request<hub::http::string_body>& req) {
    auto ct = req.find(hub::http::field::content_type);
    return ct == req.end() ? "" : std::string(ct->value());
  }

  // A request handed to loop(), answered later; with no room, 503 now (true).
  bool handOver(Ask ask, Answer& now, Later later) {
    pump();
    if (desk_.hand(LaterHandle{std::make_shared<Later>(std::move(later))}, ask)) return false;
    now = error(503, "overloaded", "too many requests are waiting for the ESP; try again");
    return true;
  }
  // The network side's turn: loop()'s answers and the live channel's messages.
  void networkTurn() {
    pump();
    live_.pump();
  }
  // AsyncTCP's poll of each connection, every 500 ms (CONFIG_ASYNC_TCP_POLL_TIMER, lwIP's slow timer).
  void poll() {
    pollTimer_.expires_after(std::chrono::milliseconds(500));
    pollTimer_.async_wait([this](boost::beast::error_code ec) {
      if (ec) return;
      networkTurn();
      poll();
    });
  }
  // loop()'s answers, each to its request.
  void pump() {
    desk_.pump([](Later& later, const uv::esp::Answer& a) {
      later(Answer{a.status, a.plainText ? "text/plain" : "application/json", a.body, {}});
    });
  }

  Answer wifi(const hub::http::request<hub::http::string_body>& req) {
    char buf[256];
    JsonWriter w(buf, sizeof buf);
    if (req.method() == hub::http::verb::post) {
      if (gate_.held()) return flashBusy();  // the ESP stores the settings on its flash
      nlohmann::json body = nlohmann::json::parse(req.body(), nullptr, false);
      if (body.is_discarded() || req.body().size() > 1024) return error(400, "bad_json", "send {apPassword?, staSsid?, staPassword?} as JSON, under 1 KB");
      RequestError e{};
      if (!applyWifi(uvtest::View{&body}, wifi_, e)) return error(400, e.code, e.message, e.path);
      flash_.callbackOperation([] { return true; });  // the ESP writes /wifi.json here
    }
    writeWifi(w, wifi_, false);
    return {200, "application/json", w.text(), {}};
  }

  // As app_files.cpp on the ESP: <path>.gz with its type, an ETag from the gzip trailer, 304.
  Answer appFile(const hub::http::request<hub::http::string_body>& req, const std::string& url) {
    if (gate_.held()) return flashBusy();  // the app's files are on the flash too
    char path[256];
    AppFile found = uv::esp::appFile(url.c_str(), path, sizeof path, [this](const char* p) { return std::filesystem::exists(www_ / (std::string(p + 1) + ".gz")); });
    if (found == AppFile::NotFound) return error(404, "not_found", "no such path");
    if (found == AppFile::NoApp) return error(404, "not_found", "the app is not on this hub: npm run build:esp");
    std::filesystem::path file = www_ / (std::string(path + 1) + ".gz");
    std::string gz = flash_.callbackOperation([&] { return readFile(file); });
    char etag[24] = "";
    if (gz.size() >= 8) gzipEtag(reinterpret_cast<const uint8_t*>(gz.data() + gz.size() - 8), etag);
    auto inm = req.find(hub::http::field::if_none_match);
    if (etag[0] && inm != req.end() && inm->value() == etag) return {304, "", "", {{"ETag", etag}}};
    return {200, contentType(path), std::move(gz), {{"Content-Encoding", "gzip"}, {"ETag", etag}, {"Cache-Control", cacheControl(path)}}};
  }

  // A request that would touch the flash while loop() is inside a file operation.
  static Answer flashBusy() {
    Answer a = error(kFlashBusyStatus, kFlashBusyCode, kFlashBusyMessage);
    a.headers.push_back({"Retry-After", kFlashRetryAfter});
    return a;
  }

  net::io_context& io_;
  std::filesystem::path www_, state_;
  mega::MegaRig rig_;
  RigWire wire_{rig_};
  hub::LiveSessions sessions_;
  LiveChannel live_{sessions_};
  Bridge bridge_{wire_, live_};
  uvtest::HostFlash flash_;
  FlashGate gate_;
  uvtest::HostBody body_;
  using BodyCheck = PrintIntake<uvtest::HostBody, uvtest::HostHeaderParse>;
  BodyCheck intake_{body_, bridge_, uvtest::HostHeaderParse{}};
  HandOver rings_;
  NetworkDesk<LaterHandle> desk_{rings_};
  LoopDesk<Bridge, BodyCheck> loopDesk_{rings_, bridge_, intake_};
  WifiSettings wifi_{};
  uint32_t jobs_ = 0;
  size_t fed_ = 0;
  Turn turn_ = Turn::EachPass;
  bool wakePending_ = false;
  uint32_t woken_ = 0, backlogMs_ = 0;
  net::steady_timer pollTimer_{io_};
  double budget_ = 0;
};

std::chrono::milliseconds requestDeadline{kRequestDeadlineMs};

Board board = kEsp8266;
bool accepting = false;
tcp::acceptor* acceptorPtr = nullptr;
Hub* hubPtr = nullptr;

// A connection is taken only while the board has a socket for it; the others wait in the
// backlog until one comes free, as an ESP8266's lwIP leaves a SYN unanswered without a free PCB.
void accept() {
  if (accepting || hub::SocketSlot::open >= board.tcpSockets) return;
  accepting = true;
  acceptorPtr->async_accept([](boost::beast::error_code ec, tcp::socket socket) {
    accepting = false;
    if (!ec) std::make_shared<hub::HttpSession>(std::move(socket), *hubPtr, requestDeadline)->start();
    accept();
  });
}

}  // namespace

int main(int argc, char** argv) {
  unsigned short port = 0;
  std::filesystem::path www = "firmware/esp/data/www";
  double speed = 1;
  std::string turn = "each-pass";
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string a = argv[i];
    if (a == "--port") port = static_cast<unsigned short>(std::stoi(argv[i + 1]));
    else if (a == "--www") www = argv[i + 1];
    else if (a == "--speed") speed = std::stod(argv[i + 1]);
    else if (a == "--board") board = std::string(argv[i + 1]) == "esp32" ? kEsp32 : kEsp8266;  // its sockets and /ws limits
    else if (a == "--turn") turn = argv[i + 1];  // each-pass (the ESP8266), poll, wake (the ESP32's network task)
    else if (a == "--request-deadline-ms") requestDeadline = std::chrono::milliseconds(std::stoul(argv[i + 1]));  // tests: the rule's 60 s, shorter
  }
  std::filesystem::path state = std::filesystem::temp_directory_path() / ("uv-esp-host-" + std::to_string(::getpid()));
  std::filesystem::create_directories(state);
  // The hub lives as long as whoever started it (lifeline.h): then it takes its flash with it.
  static std::filesystem::path flash;
  flash = state;
  auto started = std::chrono::steady_clock::now();
  hub::holdLifeline([started] {
    // How long one loop pass took, for the benchmarks' ratios (bench/hub.bench.ts).
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
    std::printf("loop passes: %llu in %.0f ms\n", static_cast<unsigned long long>(Hub::passes.load()), ms);
    std::fflush(stdout);
    std::error_code ignored;
    std::filesystem::remove_all(flash, ignored);
    std::_Exit(0);
  });
  net::io_context io;
  Hub hub(io, www, state, board);
  hub.setTurn(turn == "poll" ? Hub::Turn::Poll : turn == "wake" ? Hub::Turn::Woken : Hub::Turn::EachPass);
  tcp::acceptor acceptor(io, {net::ip::make_address("127.0.0.1"), port});
  acceptorPtr = &acceptor;
  hubPtr = &hub;
  hub::SocketSlot::freed = [] { net::post(acceptorPtr->get_executor(), [] { accept(); }); };
  accept();
  hub.begin();
  std::printf("listening on http://127.0.0.1:%u\n", acceptor.local_endpoint().port());
  std::fflush(stdout);
  auto last = std::chrono::steady_clock::now();
  for (;;) {
    io.poll();
    auto now = std::chrono::steady_clock::now();
    double ms = std::chrono::duration<double, std::milli>(now - last).count();
    if (ms >= 1) {
      last = now;
      hub.tick(std::min(ms, 50.0) * speed);  // a stalled host slows the Mega's time; it never jumps
    } else {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
}
