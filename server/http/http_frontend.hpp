#pragma once
// The HTTP front end: cpp-httplib's router and handlers behind our own connection handling.
//
// cpp-httplib 0.11.4 gives each connection a pool thread from accept to close, and its read timeout
// (SO_RCVTIMEO) restarts with every byte: eight clients sending a header byte every few seconds hold
// all eight threads, and stop() waits for idle keep-alive connections. Here one poller thread owns
// every connection while it is idle or still sending its request, with a real deadline for the
// whole request (head and body); only a complete request goes to a handler thread, which runs
// cpp-httplib's own parsing and routing (Server::process_request) over the buffered bytes. So slow
// clients cost a socket and a buffer, never a handler thread, and a stop closes idle and half-sent
// connections at once.
//
// The listening socket is bound without SO_REUSEPORT (cpp-httplib's default sets it, which lets a
// second server bind the same port and split the traffic): a busy port is an error.
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include <httplib.h>

namespace rupture::server {

struct FrontendLimits {
  std::chrono::milliseconds requestTimeout{10'000};  ///< first byte to last byte of one request
  std::chrono::milliseconds keepAliveTimeout{5'000};  ///< idle time allowed between requests
  std::chrono::milliseconds writeTimeout{30'000};     ///< longest stall while sending a response
  std::chrono::milliseconds stopGrace{1'000};         ///< how long stop() lets responses in flight finish
  std::size_t maxHeadBytes = 64 * 1024;               ///< request line + headers (431 above)
  std::size_t maxBodyBytes = 1 << 20;                 ///< larger bodies are answered 413 unread
  std::size_t maxBufferedBytes = 256u << 20;          ///< requests being received, all together (503 above)
  int handlerThreads = 8;                             ///< threads running handlers
  int maxConnections = 512;                           ///< open connections in all (503 above)
  int maxConnectionsPerClient = 64;                   ///< open connections from one address (503 above)
  int maxRequestsPerConnection = 100;                 ///< keep-alive requests before the server closes
};

class ConnectionHub;

class HttpFrontend : public httplib::Server {
public:
  explicit HttpFrontend(FrontendLimits limits);
  ~HttpFrontend() override;

  /// Called on each parsed request before routing (cpp-httplib's setup_request hook).
  void setRequestSetup(std::function<void(httplib::Request&)> setup) { m_setup = std::move(setup); }

  /// Connections open now (idle, reading or being answered).
  int openConnections() const;

  /// After bind_to_port: the listening socket's accept queue (cpp-httplib listens with 5). Returns
  /// false with errno set when the kernel refuses.
  bool setListenBacklog(int backlog);

  // Used by the connection hub: runs cpp-httplib's request processing on one buffered request.
  bool processBufferedRequest(httplib::Stream& stream, bool closeConnection, bool& connectionClosed);

private:
  // cpp-httplib calls this on the listening thread right after accept(): the hub adopts the socket.
  bool process_and_close_socket(socket_t sock) override;

  FrontendLimits m_limits;
  std::shared_ptr<ConnectionHub> m_hub;
  std::function<void(httplib::Request&)> m_setup;
};

}  // namespace rupture::server
