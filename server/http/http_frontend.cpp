#include "http/http_frontend.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

#include "common/log.hpp"
#include "common/problem.hpp"
#include "common/utf8.hpp"

namespace rupture::server {
namespace {

using Clock = std::chrono::steady_clock;

void addressOf(const sockaddr_storage& addr, std::string& ip, int& port) {
  char text[INET6_ADDRSTRLEN] = {};
  if (addr.ss_family == AF_INET) {
    const auto* a = reinterpret_cast<const sockaddr_in*>(&addr);
    inet_ntop(AF_INET, &a->sin_addr, text, sizeof text);
    port = ntohs(a->sin_port);
  } else if (addr.ss_family == AF_INET6) {
    const auto* a = reinterpret_cast<const sockaddr_in6*>(&addr);
    inet_ntop(AF_INET6, &a->sin6_addr, text, sizeof text);
    port = ntohs(a->sin6_port);
  }
  ip = text;
}

/// A complete HTTP response with a problem document, for answers the hub gives itself; `header`
/// names the header at fault (the problem's `field`, with "in": "header").
std::string rawProblem(int status, const std::string& detail, const std::string& header = {}) {
  ApiError error = problemForStatus(status, detail);
  if (!header.empty())
    error = ApiError(error.status(), error.type(), error.title(), error.what(), header, Json{{"in", "header"}});
  const std::string body = dumpJson(problemDocument(error));
  return "HTTP/1.1 " + std::to_string(status) + " " + statusTitle(status) +
         "\r\nContent-Type: application/problem+json\r\nContent-Length: " + std::to_string(body.size()) +
         "\r\nConnection: close\r\nX-Content-Type-Options: nosniff\r\nCache-Control: no-store\r\n\r\n" + body;
}

/// Best effort, never blocks: the connection is closed right after.
void sendNow(int fd, const std::string& bytes) {
  [[maybe_unused]] ssize_t n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
}

std::string trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n')) s.remove_suffix(1);
  return std::string(s);
}

bool equalsNoCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

/// One client connection. Owned by exactly one thread at a time: the poller while idle or
/// reading, a handler thread while its request is answered.
struct Connection {
  int fd = -1;
  std::string ip;
  int port = 0;
  std::string in;                 // received bytes not yet consumed
  std::size_t requestBytes = 0;   // length of the complete request at the front of `in`
  bool closeAfter = false;        // the rest of the stream cannot be framed (chunked, 413, errors)
  bool sentContinue = false;
  bool idle = true;               // waiting for the first byte of a request
  bool reframe = false;           // handed back with bytes of a pipelined request buffered
  Clock::time_point deadline;
  int served = 0;
};

/// Where a request's bytes end in `in`: complete, incomplete, or an error answered by the hub.
struct Framing {
  enum Kind { Incomplete, Complete, Reject } kind = Incomplete;
  std::size_t bytes = 0;       // Complete: the request's length
  bool closeAfter = false;     // Complete: close once answered
  bool expectContinue = false; // Incomplete: the client waits for 100 Continue
  int status = 0;              // Reject
  std::string detail;          // Reject
  std::string header;          // Reject: the header at fault, when one is
};

/// Frames the request at the front of `in` the way cpp-httplib reads it: a request line, header
/// lines ending in CRLF (others are skipped), an empty CRLF line, then Content-Length bytes.
Framing frameRequest(const std::string& in, const FrontendLimits& limits) {
  Framing f;
  std::size_t pos = 0;
  bool first = true;
  std::optional<std::size_t> contentLength;
  bool chunked = false, expect = false;
  int hostLines = 0;
  auto reject = [&f](int status, std::string detail, std::string header = {}) {
    f.kind = Framing::Reject;
    f.status = status;
    f.detail = std::move(detail);
    f.header = std::move(header);
    return f;
  };
  while (true) {
    const std::size_t eol = in.find('\n', pos);
    if (eol == std::string::npos) {
      if (in.size() > limits.maxHeadBytes) {
        f.kind = Framing::Reject;
        f.status = 431;
        f.detail = "the request line and headers exceed " + std::to_string(limits.maxHeadBytes) + " bytes";
      }
      return f;
    }
    const std::string_view line(in.data() + pos, eol + 1 - pos);
    pos = eol + 1;
    if (pos > limits.maxHeadBytes) {
      f.kind = Framing::Reject;
      f.status = 431;
      f.detail = "the request line and headers exceed " + std::to_string(limits.maxHeadBytes) + " bytes";
      return f;
    }
    if (first) {
      first = false;
      continue;
    }
    if (line == "\r\n") break;
    if (line.size() < 2 || line[line.size() - 2] != '\r') continue;  // cpp-httplib skips such lines
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos) continue;
    const std::string_view name = line.substr(0, colon);
    const std::string value = trim(line.substr(colon + 1));
    // cpp-httplib keeps a header value up to its first NUL: "Bearer <token>\0x" would pass as the
    // token, and two different keys "k\0y" and "k\0z" as one (RFC 9110 §5.5 forbids NUL anyway).
    if (line.find('\0') != std::string_view::npos) {
      const std::string header = toValidUtf8(std::string(name.substr(0, std::min<std::size_t>(name.find('\0'), 100))));
      return reject(400, "the header '" + header + "' holds a NUL byte, which HTTP header fields may not contain", header);
    }
    if (equalsNoCase(name, "Host") && ++hostLines > 1)
      return reject(400, "the request has more than one Host header (RFC 9112 §3.2: exactly one)", "Host");
    // cpp-httplib drops a header whose value is empty: a retry would then be taken as a new job.
    if (equalsNoCase(name, "Idempotency-Key") && value.empty())
      return reject(400, "Idempotency-Key is empty; it must be 1 to 200 visible ASCII characters (a UUID is a good choice)",
                    "Idempotency-Key");
    if (equalsNoCase(name, "Content-Length")) {
      const bool digits = !value.empty() && value.size() <= 18 &&
                          std::all_of(value.begin(), value.end(), [](char c) { return c >= '0' && c <= '9'; });
      const std::size_t n = digits ? std::stoull(value) : 0;
      if (!digits || (contentLength && *contentLength != n)) {
        f.kind = Framing::Reject;
        f.status = 400;
        f.detail = "the Content-Length header is not a single decimal number";
        f.header = "Content-Length";
        return f;
      }
      contentLength = n;
    } else if (equalsNoCase(name, "Transfer-Encoding")) {
      chunked = true;
    } else if (equalsNoCase(name, "Expect")) {
      expect = equalsNoCase(value, "100-continue");
    }
  }
  const std::size_t head = pos;
  f.kind = Framing::Complete;
  if (chunked || (contentLength && *contentLength > limits.maxBodyBytes)) {
    // Answered from the head alone (411 / 413): the body is never read, so the connection ends.
    f.bytes = head;
    f.closeAfter = true;
    return f;
  }
  const std::size_t total = head + contentLength.value_or(0);
  if (in.size() < total) {
    f.kind = Framing::Incomplete;
    f.expectContinue = expect;
    return f;
  }
  f.bytes = total;
  return f;
}

/// The Stream cpp-httplib parses and answers one request on: reads come from the buffered request
/// (end of data after it), writes go to the socket with a stall timeout, and stop once the hub
/// aborts writes.
class BufferedStream : public httplib::Stream {
public:
  BufferedStream(Connection& c, const std::atomic<bool>& abort, std::chrono::milliseconds writeTimeout)
      : m_conn(c), m_abort(abort), m_writeTimeout(writeTimeout) {}

  bool is_readable() const override { return m_pos < m_conn.requestBytes; }
  bool is_writable() const override { return waitWritable(); }

  ssize_t read(char* ptr, size_t size) override {
    const std::size_t n = std::min(size, m_conn.requestBytes - m_pos);
    std::memcpy(ptr, m_conn.in.data() + m_pos, n);
    m_pos += n;
    return static_cast<ssize_t>(n);
  }

  ssize_t write(const char* ptr, size_t size) override {
    while (true) {
      if (m_abort) return -1;
      const ssize_t n = ::send(m_conn.fd, ptr, size, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n >= 0) return n;
      if (errno == EINTR) continue;
      if (errno != EAGAIN && errno != EWOULDBLOCK) return -1;
      if (!waitWritable()) return -1;
    }
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = m_conn.ip;
    port = m_conn.port;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage addr{};
    socklen_t len = sizeof addr;
    if (getsockname(m_conn.fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0) addressOf(addr, ip, port);
  }
  socket_t socket() const override { return m_conn.fd; }

private:
  /// Waits for room in the send buffer: false after `writeTimeout` without progress or on abort.
  bool waitWritable() const {
    const auto deadline = Clock::now() + m_writeTimeout;
    while (!m_abort) {
      pollfd p{m_conn.fd, POLLOUT, 0};
      const int r = ::poll(&p, 1, 100);
      if (r > 0) return (p.revents & (POLLERR | POLLNVAL)) == 0;
      if (r < 0 && errno != EINTR) return false;
      if (Clock::now() >= deadline) return false;
    }
    return false;
  }

  Connection& m_conn;
  const std::atomic<bool>& m_abort;
  std::chrono::milliseconds m_writeTimeout;
  std::size_t m_pos = 0;
};

}  // namespace

/// Owns the connections: a poller thread for idle and reading ones, handler threads for complete
/// requests. Started by the task queue cpp-httplib creates in listen(), stopped by its shutdown().
class ConnectionHub {
public:
  ConnectionHub(HttpFrontend& frontend, FrontendLimits limits) : m_frontend(frontend), m_limits(limits) {}
  ~ConnectionHub() { stop(); }

  void start() {
    std::lock_guard lock(m_mutex);
    if (m_started) return;
    m_started = true;
    m_stopping = false;
    m_abort = false;
    m_wakeFd = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (m_wakeFd < 0) throw std::runtime_error(std::string("eventfd: ") + std::strerror(errno));
    m_poller = std::thread([this] { pollLoop(); });
    for (int i = 0; i < std::max(1, m_limits.handlerThreads); ++i) m_handlers.emplace_back([this] { handlerLoop(); });
  }

  /// Closes idle and half-sent connections now, lets responses in flight finish for up to
  /// stopGrace, then cuts the rest. Idempotent.
  void stop() {
    {
      std::lock_guard lock(m_mutex);
      if (!m_started || m_stopping) return;
      m_stopping = true;
    }
    wake();
    m_workReady.notify_all();
    if (m_poller.joinable()) m_poller.join();
    {
      std::unique_lock lock(m_mutex);
      m_idle.wait_for(lock, m_limits.stopGrace, [this] { return m_busy == 0 && m_work.empty(); });
    }
    m_abort = true;
    m_workReady.notify_all();
    for (std::thread& t : m_handlers) {
      if (t.joinable()) t.join();
    }
    m_handlers.clear();
    std::lock_guard lock(m_mutex);
    for (auto& c : m_work) closeConnectionLocked(*c);
    m_work.clear();
    for (auto& c : m_returned) closeConnectionLocked(*c);
    m_returned.clear();
    if (m_wakeFd >= 0) ::close(m_wakeFd);
    m_wakeFd = -1;
    m_started = false;
  }

  /// A socket just accepted (listening thread): counted and handed to the poller, or refused.
  void adopt(int fd) {
    sockaddr_storage addr{};
    socklen_t len = sizeof addr;
    std::string ip;
    int port = 0;
    if (getpeername(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0) addressOf(addr, ip, port);
    std::string refusal;
    {
      std::lock_guard lock(m_mutex);
      if (m_stopping || !m_started) {
        refusal = rawProblem(503, "the server is stopping");
      } else if (m_open >= m_limits.maxConnections || fd >= FD_SETSIZE) {
        refusal = rawProblem(503, "the server has too many open connections; try again shortly");
      } else if (m_perClient[ip] >= m_limits.maxConnectionsPerClient) {
        refusal = rawProblem(503, "too many open connections from this address (at most " +
                                      std::to_string(m_limits.maxConnectionsPerClient) + ")");
      } else {
        ++m_open;
        ++m_perClient[ip];
        auto c = std::make_unique<Connection>();
        c->fd = fd;
        c->ip = ip;
        c->port = port;
        c->deadline = Clock::now() + m_limits.requestTimeout;  // the first request must come promptly
        m_incomingConnections.push_back(std::move(c));
      }
    }
    if (!refusal.empty()) {
      sendNow(fd, refusal);
      ::shutdown(fd, SHUT_RDWR);
      ::close(fd);
      return;
    }
    wake();
  }

  int openConnections() const {
    std::lock_guard lock(m_mutex);
    return m_open;
  }

private:
  void wake() {
    const std::uint64_t one = 1;
    if (m_wakeFd >= 0) [[maybe_unused]] auto n = ::write(m_wakeFd, &one, sizeof one);
  }

  void closeConnectionLocked(Connection& c) {
    if (c.fd < 0) return;
    ::shutdown(c.fd, SHUT_RDWR);
    ::close(c.fd);
    c.fd = -1;
    --m_open;
    if (auto it = m_perClient.find(c.ip); it != m_perClient.end() && --it->second <= 0) m_perClient.erase(it);
  }

  void closeConnection(Connection& c) {
    std::lock_guard lock(m_mutex);
    closeConnectionLocked(c);
  }

  /// Frames what `c` has buffered: dispatches a complete request, answers a bad one, or waits.
  /// Returns false when the connection was closed.
  bool advance(std::unique_ptr<Connection>& c) {
    if (c->in.empty()) return true;
    if (c->idle) {
      c->idle = false;
      c->deadline = Clock::now() + m_limits.requestTimeout;
    }
    const Framing f = frameRequest(c->in, m_limits);
    if (f.kind == Framing::Reject) {
      sendNow(c->fd, rawProblem(f.status, f.detail, f.header));
      closeConnection(*c);
      return false;
    }
    if (f.kind == Framing::Incomplete) {
      if (f.expectContinue && !c->sentContinue) {
        sendNow(c->fd, "HTTP/1.1 100 Continue\r\n\r\n");
        c->sentContinue = true;
      }
      return true;
    }
    c->requestBytes = f.bytes;
    c->closeAfter = f.closeAfter;
    {
      std::lock_guard lock(m_mutex);
      m_work.push_back(std::move(c));
    }
    m_workReady.notify_one();
    return true;
  }

  void pollLoop() {
    std::vector<std::unique_ptr<Connection>> open;
    std::vector<pollfd> fds;
    char buffer[64 * 1024];
    while (true) {
      {
        std::lock_guard lock(m_mutex);
        if (m_stopping) break;
        for (auto& c : m_incomingConnections) open.push_back(std::move(c));
        m_incomingConnections.clear();
        for (auto& c : m_returned) open.push_back(std::move(c));
        m_returned.clear();
      }
      // Connections handed back with a pipelined request already buffered go straight on.
      for (auto& c : open) {
        if (c && c->reframe) {
          c->reframe = false;
          advance(c);
        }
      }
      std::erase_if(open, [](const std::unique_ptr<Connection>& c) { return !c || c->fd < 0; });

      const auto now = Clock::now();
      auto next = now + std::chrono::seconds(1);
      for (auto& c : open) {
        if (c->deadline <= now) {
          if (!c->idle) sendNow(c->fd, rawProblem(408, "the request was not complete within " +
                                                            std::to_string(m_limits.requestTimeout.count()) + " ms"));
          closeConnection(*c);
        } else {
          next = std::min(next, c->deadline);
        }
      }
      std::erase_if(open, [](const std::unique_ptr<Connection>& c) { return c->fd < 0; });

      fds.clear();
      fds.push_back({m_wakeFd, POLLIN, 0});
      for (auto& c : open) fds.push_back({c->fd, POLLIN, 0});
      const auto waitMs = std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now()).count() + 1;
      const int ready = ::poll(fds.data(), fds.size(), static_cast<int>(std::clamp<long long>(waitMs, 0, 1000)));
      if (ready < 0 && errno != EINTR) {
        logLine(std::string("http poller: poll failed: ") + std::strerror(errno));
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        continue;
      }
      if (fds[0].revents & POLLIN) {
        std::uint64_t drained = 0;
        [[maybe_unused]] auto n = ::read(m_wakeFd, &drained, sizeof drained);
      }
      for (std::size_t i = 1; i < fds.size(); ++i) {
        if (fds[i].revents == 0) continue;
        std::unique_ptr<Connection>& c = open[i - 1];
        try {
          receive(c, open, buffer, sizeof buffer);
        } catch (const std::exception& e) {  // out of memory: this connection ends, the server goes on
          logLine(std::string("http: dropping a connection: ") + e.what());
          if (c) closeConnection(*c);
          c.reset();
        }
      }
      std::erase_if(open, [](const std::unique_ptr<Connection>& c) { return !c || c->fd < 0; });
    }
    // Stopping: idle and half-sent connections end now.
    std::lock_guard lock(m_mutex);
    for (auto& c : open) {
      if (c) closeConnectionLocked(*c);
    }
    for (auto& c : m_incomingConnections) closeConnectionLocked(*c);
    m_incomingConnections.clear();
  }

  /// Reads what `c` has sent and frames it; `c` is reset when the connection ended or moved on.
  void receive(std::unique_ptr<Connection>& c, const std::vector<std::unique_ptr<Connection>>& open, char* buffer,
               std::size_t capacity) {
    const ssize_t n = ::recv(c->fd, buffer, capacity, MSG_DONTWAIT);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
      closeConnection(*c);
      c.reset();
      return;
    }
    if (n < 0) return;
    // Requests still arriving share one memory budget, so that many slow bodies cannot exhaust
    // memory (each may be up to maxBodyBytes).
    std::size_t buffered = static_cast<std::size_t>(n);
    for (const auto& other : open) buffered += other ? other->in.size() : 0;
    if (buffered > m_limits.maxBufferedBytes) {
      sendNow(c->fd, rawProblem(503, "the server is receiving too many request bodies at once; try again"));
      closeConnection(*c);
      c.reset();
      return;
    }
    c->in.append(buffer, static_cast<std::size_t>(n));
    if (!advance(c)) c.reset();
  }

  void handlerLoop() {
    while (true) {
      std::unique_ptr<Connection> c;
      {
        std::unique_lock lock(m_mutex);
        m_workReady.wait(lock, [this] { return m_abort || !m_work.empty() || (m_stopping && m_busy == 0 && m_work.empty()); });
        if (m_abort || m_work.empty()) return;
        c = std::move(m_work.front());
        m_work.pop_front();
        ++m_busy;
      }
      serve(*c);
      {
        std::lock_guard lock(m_mutex);
        --m_busy;
        if (c->fd >= 0) {
          if (m_stopping) {
            closeConnectionLocked(*c);
          } else {
            m_returned.push_back(std::move(c));
          }
        }
      }
      m_idle.notify_all();
      wake();
    }
  }

  /// Answers the buffered request with cpp-httplib; nothing thrown may leave this thread.
  void serve(Connection& c) {
    ++c.served;
    const bool closeAfter =
        c.closeAfter || m_stopping || c.served >= m_limits.maxRequestsPerConnection;
    bool clientClosed = false;
    bool ok = false;
    try {
      BufferedStream stream(c, m_abort, m_limits.writeTimeout);
      ok = m_frontend.processBufferedRequest(stream, closeAfter, clientClosed);
    } catch (const std::exception& e) {
      logLine(std::string("http: request processing failed: ") + e.what());
    } catch (...) {
      logLine("http: request processing failed (non-standard exception)");
    }
    c.in.erase(0, c.requestBytes);
    c.requestBytes = 0;
    c.sentContinue = false;
    if (!ok || clientClosed || closeAfter) {
      closeConnection(c);
      return;
    }
    c.idle = c.in.empty();
    c.reframe = !c.idle;
    c.deadline = Clock::now() + (c.idle ? m_limits.keepAliveTimeout : m_limits.requestTimeout);
  }

  HttpFrontend& m_frontend;
  const FrontendLimits m_limits;

  mutable std::mutex m_mutex;
  std::condition_variable m_workReady;
  std::condition_variable m_idle;
  bool m_started = false;
  std::atomic<bool> m_stopping{false};
  std::atomic<bool> m_abort{false};
  int m_wakeFd = -1;
  int m_open = 0;
  int m_busy = 0;
  std::map<std::string, int> m_perClient;
  std::vector<std::unique_ptr<Connection>> m_incomingConnections;
  std::deque<std::unique_ptr<Connection>> m_work;
  std::vector<std::unique_ptr<Connection>> m_returned;
  std::thread m_poller;
  std::vector<std::thread> m_handlers;
};

namespace {

/// cpp-httplib's task queue, replaced: a task is "adopt this socket", run at once on the listening
/// thread; shutdown() (end of listen()) stops the hub.
class HubTaskQueue : public httplib::TaskQueue {
public:
  explicit HubTaskQueue(std::shared_ptr<ConnectionHub> hub) : m_hub(std::move(hub)) { m_hub->start(); }
  void enqueue(std::function<void()> fn) override { fn(); }
  void shutdown() override { m_hub->stop(); }

private:
  std::shared_ptr<ConnectionHub> m_hub;
};

}  // namespace

HttpFrontend::HttpFrontend(FrontendLimits limits)
    : m_limits(limits), m_hub(std::make_shared<ConnectionHub>(*this, limits)) {
  new_task_queue = [hub = m_hub] { return new HubTaskQueue(hub); };
  set_payload_max_length(limits.maxBodyBytes);
  // Only what cpp-httplib announces in its Keep-Alive header: the hub enforces both.
  set_keep_alive_max_count(static_cast<std::size_t>(std::max(1, limits.maxRequestsPerConnection)));
  set_keep_alive_timeout(std::max<time_t>(1, std::chrono::duration_cast<std::chrono::seconds>(limits.keepAliveTimeout).count()));
  // SO_REUSEADDR only (restart while old connections linger in TIME_WAIT); without SO_REUSEPORT a
  // port another server listens on cannot be bound.
  set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
}

HttpFrontend::~HttpFrontend() { m_hub->stop(); }

int HttpFrontend::openConnections() const { return m_hub->openConnections(); }

bool HttpFrontend::setListenBacklog(int backlog) {
  // listen() again on a listening socket only changes its queue's length (Linux).
  const socket_t sock = svr_sock_;
  return sock != INVALID_SOCKET && ::listen(sock, backlog) == 0;
}

bool HttpFrontend::process_and_close_socket(socket_t sock) {
  try {
    m_hub->adopt(sock);  // on the listening thread: nothing may escape into cpp-httplib's accept loop
  } catch (const std::exception& e) {
    ::close(sock);
    logLine(std::string("http: cannot take a connection: ") + e.what());
  }
  return true;
}

bool HttpFrontend::processBufferedRequest(httplib::Stream& stream, bool closeConnection, bool& connectionClosed) {
  return process_request(stream, closeConnection, connectionClosed, m_setup);
}

}  // namespace rupture::server
