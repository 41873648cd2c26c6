// Definitions for server_test_support.hpp (no tests here).
#include "server_test_support.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

namespace rupture::server::test {

Json smallInputs() {
  Json spec = Json::parse(readText(exampleFile()));
  spec.erase("scenario");
  // VL needs no preliminary run: about 0.6 s on one core at 1e6/s. (Runs that do need one cache it
  // in the server's data directory.)
  spec["loading"]["initial_velocity"] = "VL";
  spec["loading"]["strain_rate"] = 1e6;
  return spec;
}

ChildServer::ChildServer(const std::filesystem::path& dataDir, const std::vector<std::string>& extra) {
  int out[2];
  if (pipe(out) != 0) throw std::runtime_error("pipe failed");
  std::vector<std::string> args = {RUPTURE_SERVER, "--port", "0", "--bind", "127.0.0.1",
                                   "--data-dir", dataDir.string(), "--workers", "1", "--threads-per-run", "1"};
  args.insert(args.end(), extra.begin(), extra.end());
  m_pid = fork();
  if (m_pid == 0) {
    dup2(out[1], STDOUT_FILENO);
    close(out[0]);
    close(out[1]);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(out[1]);
  m_stdout = out[0];
  // First stdout line: "rupture-server listening on http://127.0.0.1:<port>".
  std::string line;
  char c;
  while (read(m_stdout, &c, 1) == 1 && c != '\n') line += c;
  const auto colon = line.rfind(':');
  if (line.find("listening on") == std::string::npos || colon == std::string::npos) {
    throw std::runtime_error("rupture-server did not start: '" + line + "'");
  }
  m_port = std::stoi(line.substr(colon + 1));
}

ChildServer::~ChildServer() {
  if (m_pid > 0) {
    kill(m_pid, SIGKILL);
    waitpid(m_pid, nullptr, 0);
  }
  if (m_stdout >= 0) close(m_stdout);
}

int ChildServer::stop(int signal, double seconds) {
  kill(m_pid, signal);
  int status = 0;
  const bool exited = waitFor([&] { return waitpid(m_pid, &status, WNOHANG) == m_pid; }, seconds);
  if (!exited) return -1;
  m_pid = -1;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

int runServerToExit(const std::vector<std::string>& args, std::string& err, double seconds) {
  int pipeErr[2];
  if (pipe(pipeErr) != 0) throw std::runtime_error("pipe failed");
  std::vector<std::string> argvText = {RUPTURE_SERVER};
  argvText.insert(argvText.end(), args.begin(), args.end());
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(pipeErr[1], STDERR_FILENO);
    const int devNull = open("/dev/null", O_WRONLY);
    if (devNull >= 0) dup2(devNull, STDOUT_FILENO);
    close(pipeErr[0]);
    close(pipeErr[1]);
    std::vector<char*> argv;
    for (auto& a : argvText) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(pipeErr[1]);
  fcntl(pipeErr[0], F_SETFL, O_NONBLOCK);
  int status = 0;
  bool exited = false;
  char buf[4096];
  const auto readAvailable = [&] {
    ssize_t n;
    while ((n = read(pipeErr[0], buf, sizeof buf)) > 0) err.append(buf, static_cast<std::size_t>(n));
  };
  exited = waitFor([&] {
    readAvailable();
    return waitpid(pid, &status, WNOHANG) == pid;
  }, seconds);
  if (!exited) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
  }
  readAvailable();
  close(pipeErr[0]);
  if (!exited) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string rawExchange(int port, const std::string& request, double seconds) {
  int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return {};
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // loopback only
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    return {};
  }
  std::size_t sent = 0;
  while (sent < request.size()) {
    const ssize_t n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;  // the server may close early (411, 413): keep what it answered
    sent += static_cast<std::size_t>(n);
  }
  std::string out;
  char buf[4096];
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    out.append(buf, static_cast<std::size_t>(n));
    // Stop at the end of the first response when its length is known (keep-alive may hold on).
    const std::size_t headerEnd = out.find("\r\n\r\n");
    if (headerEnd != std::string::npos) {
      std::string headers = out.substr(0, headerEnd);
      for (char& c : headers) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      const std::size_t cl = headers.find("\r\ncontent-length:");
      if (cl != std::string::npos &&
          out.size() >= headerEnd + 4 + std::stoul(headers.substr(cl + 17))) {
        break;
      }
    }
  }
  ::close(fd);
  return out;
}

int rawStatus(const std::string& response) {
  if (response.rfind("HTTP/1.", 0) != 0 || response.size() < 12) return -1;
  return std::atoi(response.substr(9, 3).c_str());
}

std::string rawBody(const std::string& response) {
  const std::size_t p = response.find("\r\n\r\n");
  return p == std::string::npos ? std::string() : response.substr(p + 4);
}

// The small sample stops shortly after its peak stress, so a run's length is set by the strain rate:
// about 0.6 s at 1e6/s, 2 s at 1e5/s and 35 s at 5e3/s on one core.
RunLengthKnob runLengthKnob() { return {"loading.strain_rate", 1e6, 1e5, 5e3}; }

Json twoStrainRates() { return Json::array({1e6, 1e7}); }

bool wellFormedXml(const std::string& text, std::string& error) {
  std::vector<std::string> stack;
  std::size_t i = 0;
  bool sawRoot = false;
  while (i < text.size()) {
    if (text[i] != '<') {
      if (text[i] == '&') {
        const std::size_t semi = text.find(';', i);
        const std::string entity = semi == std::string::npos ? "" : text.substr(i, semi - i + 1);
        static const std::set<std::string> ok = {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"};
        if (!ok.count(entity) && entity.rfind("&#", 0) != 0) {
          error = "bad entity at " + std::to_string(i);
          return false;
        }
      }
      ++i;
      continue;
    }
    if (text.compare(i, 5, "<?xml") == 0) {
      i = text.find("?>", i);
      if (i == std::string::npos) { error = "unterminated declaration"; return false; }
      i += 2;
      continue;
    }
    if (text.compare(i, 4, "<!--") == 0) {
      i = text.find("-->", i);
      if (i == std::string::npos) { error = "unterminated comment"; return false; }
      i += 3;
      continue;
    }
    const std::size_t end = text.find('>', i);
    if (end == std::string::npos) { error = "unterminated tag at " + std::to_string(i); return false; }
    std::string tag = text.substr(i + 1, end - i - 1);
    i = end + 1;
    if (!tag.empty() && tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (stack.empty() || stack.back() != name) {
        error = "closing </" + name + "> does not match <" + (stack.empty() ? "" : stack.back()) + ">";
        return false;
      }
      stack.pop_back();
      continue;
    }
    const bool selfClosing = !tag.empty() && tag.back() == '/';
    if (selfClosing) tag.pop_back();
    const std::size_t nameEnd = tag.find_first_of(" \t\n");
    const std::string name = tag.substr(0, nameEnd);
    if (name.empty()) { error = "empty tag name"; return false; }
    // Attributes: name="value" pairs.
    std::size_t p = nameEnd == std::string::npos ? tag.size() : nameEnd;
    while (p < tag.size()) {
      while (p < tag.size() && std::isspace(static_cast<unsigned char>(tag[p]))) ++p;
      if (p >= tag.size()) break;
      const std::size_t eq = tag.find('=', p);
      if (eq == std::string::npos || eq + 1 >= tag.size() || (tag[eq + 1] != '"' && tag[eq + 1] != '\'')) {
        error = "unquoted attribute in <" + name + ">";
        return false;
      }
      const std::size_t close = tag.find(tag[eq + 1], eq + 2);
      if (close == std::string::npos) { error = "unterminated attribute in <" + name + ">"; return false; }
      if (tag.substr(eq + 2, close - eq - 2).find('<') != std::string::npos) {
        error = "'<' inside an attribute of <" + name + ">";
        return false;
      }
      p = close + 1;
    }
    if (stack.empty()) {
      if (sawRoot) { error = "more than one root element"; return false; }
      sawRoot = true;
    }
    if (!selfClosing) stack.push_back(name);
  }
  if (!stack.empty()) { error = "unclosed <" + stack.back() + ">"; return false; }
  if (!sawRoot) { error = "no root element"; return false; }
  return true;
}

std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false, any = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') { field += '"'; ++i; }
      else if (c == '"') quoted = false;
      else field += c;
      continue;
    }
    if (c == '"') { quoted = true; any = true; }
    else if (c == ',') { row.push_back(field); field.clear(); any = true; }
    else if (c == '\r') {}
    else if (c == '\n') { row.push_back(field); rows.push_back(row); row.clear(); field.clear(); any = false; }
    else { field += c; any = true; }
  }
  if (any || !field.empty()) { row.push_back(field); rows.push_back(row); }
  return rows;
}

}  // namespace rupture::server::test
