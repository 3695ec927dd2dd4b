// GuardedHttpServer against slow clients, over real loopback sockets: slow
// or idle connections hold no worker thread, and a request whose head or
// body does not arrive in time is answered 408 and closed. The bounds are
// generous (seconds where the server needs milliseconds): they tell "cut
// by the server" from "never cut", not how fast.
#include "server/http/guarded_http_server.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace seaplan::server {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;
using std::chrono::seconds;

// A compressible text of 190 KB.
std::string Script() {
  std::string script;
  for (int i = 0; i < 5000; ++i) script += "function f" + std::to_string(i) + "() { return 1; }\n";
  return script;
}

class GuardedHttpServerTest : public ::testing::Test {
 protected:
  void StartServer(const GuardedHttpServer::Limits& limits) {
    server_ = std::make_unique<GuardedHttpServer>(limits, nullptr);
    server_->Get("/script.js", [](const httplib::Request&, httplib::Response& res) {
      res.set_content(Script(), "application/javascript");
    });
    server_->Get("/ping", [](const httplib::Request&, httplib::Response& res) {
      res.set_content("pong", "text/plain");
    });
    server_->Post("/size", [](const httplib::Request& req, httplib::Response& res) {
      res.set_content(std::to_string(req.body.size()), "text/plain");
    });
    port_ = server_->bind_to_any_port("127.0.0.1");
    ASSERT_GT(port_, 0);
    listener_ = std::thread([this] { server_->listen_after_bind(); });
  }

  void TearDown() override {
    for (int fd : sockets_) ::close(fd);
    if (server_) server_->stop();
    if (listener_.joinable()) listener_.join();
    if (server_) server_->StopConnections();
  }

  // A raw client socket connected to the server (closed by TearDown).
  int Connect() {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(port_));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
    sockets_.push_back(fd);
    return fd;
  }

  httplib::Client Client(seconds timeout) {
    httplib::Client client("127.0.0.1", port_);
    client.set_connection_timeout(timeout);
    client.set_read_timeout(timeout);
    client.set_write_timeout(timeout);
    return client;
  }

  std::unique_ptr<GuardedHttpServer> server_;
  std::thread listener_;
  int port_ = 0;
  std::vector<int> sockets_;
};

// Sends `text` one byte every `every` until the server closes the socket or
// `limit` passes; returns what the server sent back and whether it closed.
struct Dribbled {
  std::string received;
  bool closed_by_server = false;
};
Dribbled Dribble(int fd, const std::string& text, milliseconds every, seconds limit) {
  Dribbled out;
  const auto end = Clock::now() + limit;
  std::size_t sent = 0;
  while (Clock::now() < end) {
    if (sent < text.size()) {
      if (::send(fd, text.data() + sent, 1, MSG_NOSIGNAL) != 1) {
        out.closed_by_server = true;
        break;
      }
      ++sent;
    }
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(every.count())) > 0) {
      char buffer[1024];
      const ssize_t n = ::recv(fd, buffer, sizeof(buffer), 0);
      if (n <= 0) {
        out.closed_by_server = true;
        break;
      }
      out.received.append(buffer, static_cast<std::size_t>(n));
    }
  }
  return out;
}

TEST_F(GuardedHttpServerTest, ServesBufferedAndStreamedBodiesAndKeepsConnectionsAlive) {
  GuardedHttpServer::Limits limits;
  limits.worker_threads = 2;
  limits.max_buffered_body_bytes = 1024;
  StartServer(limits);
  httplib::Client client = Client(seconds(30));
  client.set_keep_alive(true);
  for (int i = 0; i < 3; ++i) {
    auto res = client.Get("/ping");
    ASSERT_TRUE(res) << httplib::to_string(res.error());
    EXPECT_EQ(res->body, "pong");
  }
  // Below the buffering limit (read by the waiting room) and above it (read
  // by the worker), on the same connection.
  for (std::size_t size : {std::size_t{100}, std::size_t{3} << 20}) {
    auto res = client.Post("/size", std::string(size, 'x'), "application/octet-stream");
    ASSERT_TRUE(res) << httplib::to_string(res.error());
    EXPECT_EQ(res->body, std::to_string(size));
  }
}

// More slow clients than worker threads, each still sending its head a byte
// at a time: a normal request is served meanwhile. (With a thread per
// connection, as httplib::Server has, both threads stay in the slow heads'
// reads and the request waits as long as they dribble.)
TEST_F(GuardedHttpServerTest, SlowHeadsDoNotHoldTheWorkers) {
  GuardedHttpServer::Limits limits;
  limits.worker_threads = 2;
  limits.head_timeout = seconds(60);  // not cut during the test
  StartServer(limits);
  constexpr int kSlowConnections = 20;
  std::vector<int> slow;
  slow.reserve(kSlowConnections);
  for (int i = 0; i < kSlowConnections; ++i) slow.push_back(Connect());
  std::atomic<bool> done{false};
  std::thread dribbler([&] {
    const std::string head = "GET /ping HTTP/1.1\r\nHost: x\r\nX-Slow: " + std::string(4096, 'a');
    for (std::size_t b = 0; b < head.size() && !done; ++b) {
      for (int fd : slow) (void)!::send(fd, head.data() + b, 1, MSG_NOSIGNAL);
      std::this_thread::sleep_for(milliseconds(50));
    }
  });
  std::this_thread::sleep_for(milliseconds(500));  // every slow head has begun
  httplib::Client client = Client(seconds(20));
  auto res = client.Get("/ping");
  done = true;
  dribbler.join();
  ASSERT_TRUE(res) << httplib::to_string(res.error());
  EXPECT_EQ(res->body, "pong");
}

TEST_F(GuardedHttpServerTest, AHeadThatDoesNotArriveInTimeIsAnswered408AndClosed) {
  GuardedHttpServer::Limits limits;
  limits.head_timeout = seconds(1);
  StartServer(limits);
  const int fd = Connect();
  const Dribbled d = Dribble(fd, "GET /ping HTTP/1.1\r\nX-Slow: " + std::string(4096, 'a'),
                             milliseconds(100), seconds(30));
  EXPECT_TRUE(d.closed_by_server);
  EXPECT_EQ(d.received.rfind("HTTP/1.1 408", 0), 0u) << d.received;
}

TEST_F(GuardedHttpServerTest, ABodyBelowTheMinimumRateIsCut) {
  GuardedHttpServer::Limits limits;
  limits.head_timeout = seconds(1);
  limits.min_body_bytes_per_s = 1000;
  limits.max_buffered_body_bytes = 1000;
  StartServer(limits);
  // 10 bytes/s: a small body (the waiting room reads it) and a large one
  // (a worker reads it).
  for (std::size_t size : {std::size_t{500}, std::size_t{100000}}) {
    SCOPED_TRACE(size);
    const int fd = Connect();
    const std::string head =
        "POST /size HTTP/1.1\r\nHost: x\r\nContent-Length: " + std::to_string(size) + "\r\n\r\n";
    ASSERT_EQ(::send(fd, head.data(), head.size(), MSG_NOSIGNAL),
              static_cast<ssize_t>(head.size()));
    const Dribbled d = Dribble(fd, std::string(size, 'x'), milliseconds(100), seconds(30));
    EXPECT_TRUE(d.closed_by_server);
    EXPECT_EQ(d.received.find("200 OK"), std::string::npos) << d.received;
  }
}

// A large body (read by a worker) sent faster than the minimum rate but
// longer than max_body_time: cut at the time limit, and the only worker is
// free again for the next client. (Without the limit the worker stays in
// this body for size / rate.)
TEST_F(GuardedHttpServerTest, ALargeBodyIsCutAtTheBodyTimeEvenAboveTheMinimumRate) {
  GuardedHttpServer::Limits limits;
  limits.worker_threads = 1;
  limits.head_timeout = seconds(1);
  limits.min_body_bytes_per_s = 1000;
  limits.max_body_time = seconds(2);
  limits.max_buffered_body_bytes = 1000;
  StartServer(limits);
  const int fd = Connect();
  constexpr std::size_t kSize = 200000;  // 40 s at the 5000 bytes/s sent below
  const std::string head =
      "POST /size HTTP/1.1\r\nHost: x\r\nContent-Length: " + std::to_string(kSize) + "\r\n\r\n";
  ASSERT_EQ(::send(fd, head.data(), head.size(), MSG_NOSIGNAL), static_cast<ssize_t>(head.size()));
  const auto started = Clock::now();
  const std::string chunk(500, 'x');
  std::string received;
  bool closed_by_server = false;
  for (std::size_t sent = 0; sent < kSize && Clock::now() - started < seconds(60);) {
    if (::send(fd, chunk.data(), chunk.size(), MSG_NOSIGNAL) !=
        static_cast<ssize_t>(chunk.size())) {
      closed_by_server = true;
      break;
    }
    sent += chunk.size();
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) > 0) {
      char buffer[1024];
      const ssize_t n = ::recv(fd, buffer, sizeof(buffer), 0);
      if (n <= 0) {
        closed_by_server = true;
        break;
      }
      received.append(buffer, static_cast<std::size_t>(n));
    }
  }
  const auto took = Clock::now() - started;
  EXPECT_TRUE(closed_by_server);
  EXPECT_EQ(received.find("200 OK"), std::string::npos) << received;
  // Cut at about 3 s (grace + body time); 20 s tells "cut" from "read whole".
  EXPECT_LT(took, seconds(20));
  httplib::Client client = Client(seconds(20));
  auto res = client.Get("/ping");
  ASSERT_TRUE(res) << httplib::to_string(res.error());
  EXPECT_EQ(res->body, "pong");
}

// A client accepting brotli and gzip (as browsers do) gets gzip: httplib
// would spend its slowest brotli setting on every answer.
TEST_F(GuardedHttpServerTest, AnswersAreGzipForClientsThatAlsoAcceptBrotli) {
  StartServer(GuardedHttpServer::Limits{});
  const std::string script = Script();
  httplib::Client client = Client(seconds(20));
  client.set_decompress(false);
  for (const char* accepted : {"gzip, deflate, br", "br;q=1.0, gzip;q=0.8", "BR, gzip"}) {
    SCOPED_TRACE(accepted);
    auto res = client.Get("/script.js", {{"Accept-Encoding", accepted}});
    ASSERT_TRUE(res) << httplib::to_string(res.error());
    EXPECT_EQ(res->get_header_value("Content-Encoding"), "gzip");
    EXPECT_LT(res->body.size(), script.size());
  }
  // Brotli alone: uncompressed.
  auto res = client.Get("/script.js", {{"Accept-Encoding", "br"}});
  ASSERT_TRUE(res) << httplib::to_string(res.error());
  EXPECT_FALSE(res->has_header("Content-Encoding"));
  EXPECT_EQ(res->body, script);
}

// Idle connections (no byte sent) beyond the waiting room's capacity: the
// oldest are closed, and a new client is still served.
TEST_F(GuardedHttpServerTest, TheWaitingRoomClosesItsOldestConnectionsBeyondItsCapacity) {
  GuardedHttpServer::Limits limits;
  limits.worker_threads = 1;
  limits.max_waiting_connections = 8;
  limits.head_timeout = seconds(60);
  StartServer(limits);
  std::vector<int> idle;
  for (int i = 0; i < 16; ++i) {
    idle.push_back(Connect());
    std::this_thread::sleep_for(milliseconds(20));  // an order of arrival
  }
  httplib::Client client = Client(seconds(20));
  auto res = client.Get("/ping");
  ASSERT_TRUE(res) << httplib::to_string(res.error());
  EXPECT_EQ(res->body, "pong");
  // The first one connected is among those closed (EOF, or the 408 then EOF).
  pollfd p{idle.front(), POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 20000), 1);
  char buffer[512];
  ssize_t n = ::recv(idle.front(), buffer, sizeof(buffer), 0);
  while (n > 0) n = ::recv(idle.front(), buffer, sizeof(buffer), 0);
  EXPECT_EQ(n, 0);
}

}  // namespace
}  // namespace seaplan::server
