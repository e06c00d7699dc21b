#include "test/support/modbus_axis_server.hpp"

#include <modbus/modbus.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <map>
#include <vector>

namespace rangefit::sim {

namespace fhpp = drivers::fhpp;

namespace {

struct Client {
  modbus_t* ctx = nullptr;
  int id = 0;
};

std::uint16_t be16(const std::uint8_t* p) { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }

void put_be16(std::vector<std::uint8_t>& v, unsigned x) {
  v.push_back(static_cast<std::uint8_t>(x >> 8));
  v.push_back(static_cast<std::uint8_t>(x & 0xFFu));
}

// MBAP header (transaction id echoed, protocol 0, length) + unit + function code.
std::vector<std::uint8_t> reply_head(const std::uint8_t* req, unsigned pdu_bytes) {
  std::vector<std::uint8_t> v{req[0], req[1], 0, 0};
  put_be16(v, pdu_bytes + 1);
  v.push_back(req[6]);
  v.push_back(req[7]);
  return v;
}

fhpp::Registers read_registers(const std::uint8_t* p) {
  fhpp::Registers r{};
  for (int k = 0; k < fhpp::kTelegramRegisters; ++k) r[k] = be16(p + 2 * k);
  return r;
}

}  // namespace

SimAxisServer::SimAxisServer(SimFhppDrive& drive, SimAxisServerConfig config,
                             const hal::Clock* clock)
    : drive_(drive), config_(std::move(config)), clock_(clock), byte_order_(config_.byte_order) {}

SimAxisServer::~SimAxisServer() { stop(); }

hal::Timestamp SimAxisServer::now() const { return clock_ ? clock_->now() : hal::monotonic_now(); }

hal::Status SimAxisServer::start() {
  if (running_) return hal::Status::Ok();
  modbus_t* ctx = modbus_new_tcp(config_.host.c_str(), config_.port);
  if (ctx == nullptr) return hal::Status::Error("sim axis: invalid address " + config_.host);
  const int fd = modbus_tcp_listen(ctx, 8);
  if (fd == -1) {
    const int err = errno;
    modbus_free(ctx);
    return hal::Status::Error("sim axis: cannot listen on " + config_.host + ":" +
                              std::to_string(config_.port) + ": " + modbus_strerror(err));
  }
  sockaddr_in addr{};
  socklen_t len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  listen_ctx_ = ctx;
  listen_fd_ = fd;
  running_ = true;
  thread_ = std::thread([this] { run(); });
  return hal::Status::Ok();
}

void SimAxisServer::stop() {
  if (!running_.exchange(false)) return;
  if (thread_.joinable()) thread_.join();
  ::close(listen_fd_);
  modbus_free(static_cast<modbus_t*>(listen_ctx_));
  listen_fd_ = -1;
  listen_ctx_ = nullptr;
}

void SimAxisServer::run() {
  auto* listen_ctx = static_cast<modbus_t*>(listen_ctx_);
  std::map<int, Client> clients;  // by socket
  int next_id = 1;
  std::vector<std::uint8_t> req(MODBUS_TCP_MAX_ADU_LENGTH);
  while (running_) {
    std::vector<pollfd> fds{{listen_fd_, POLLIN, 0}};
    for (const auto& [fd, c] : clients) fds.push_back({fd, POLLIN, 0});
    const int ready = ::poll(fds.data(), fds.size(), 5);
    drive_.tick(now());  // the drive's timers run without requests too
    if (ready <= 0) continue;
    if (fds[0].revents & POLLIN) {
      int lfd = listen_fd_;
      const int fd = modbus_tcp_accept(listen_ctx, &lfd);
      if (fd >= 0) {
        Client c{modbus_new_tcp(config_.host.c_str(), port_), next_id++};
        modbus_set_socket(c.ctx, fd);
        modbus_set_byte_timeout(c.ctx, 0, 50000);
        clients[fd] = c;
        ++connections_;
      }
    }
    for (std::size_t i = 1; i < fds.size(); ++i) {
      if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const Client c = clients[fds[i].fd];
      const int n = modbus_receive(c.ctx, req.data());
      bool keep = n >= 0;
      if (n > 0) keep = serve(c.ctx, fds[i].fd, c.id, req.data(), n);
      if (!keep) {
        drive_.disconnected(c.id);
        modbus_close(c.ctx);
        modbus_free(c.ctx);
        clients.erase(fds[i].fd);
        --connections_;
      }
    }
  }
  for (auto& [fd, c] : clients) {
    drive_.disconnected(c.id);
    modbus_close(c.ctx);
    modbus_free(c.ctx);
  }
  connections_ = 0;
}

bool SimAxisServer::serve(void* ctx_ptr, int fd, int client, const std::uint8_t* req, int len) {
  auto* ctx = static_cast<modbus_t*>(ctx_ptr);
  ++requests_;
  const fhpp::ByteOrder order = byte_order_;
  const int unit = req[6];
  const int fc = req[7];
  if (config_.unit_id != 0 && unit != config_.unit_id && unit != 0xFF) {
    return modbus_reply_exception(ctx, req, MODBUS_EXCEPTION_GATEWAY_TARGET) != -1;
  }
  if (const int code = exception_; code != 0) return modbus_reply_exception(ctx, req, code) != -1;
  const auto bad_address = [&] {
    return modbus_reply_exception(ctx, req, MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS) != -1;
  };
  std::vector<std::uint8_t> rsp;
  const auto append_input = [&](int count) {
    const fhpp::Registers in = fhpp::encode(drive_.read(now(), client), order);
    rsp.push_back(static_cast<std::uint8_t>(2 * count));
    for (int k = 0; k < count; ++k) put_be16(rsp, in[k]);
  };
  if (fc == MODBUS_FC_WRITE_AND_READ_REGISTERS && config_.supports_read_write && len >= 17 + 8) {
    const unsigned read_addr = be16(req + 8), read_n = be16(req + 10);
    const unsigned write_addr = be16(req + 12), write_n = be16(req + 14);
    if (read_addr != 0 || write_addr != 0 || write_n != 4 || read_n < 1 || read_n > 4) {
      return bad_address();
    }
    const auto out = fhpp::decode_output(read_registers(req + 17), order);
    drive_.write(*out, now(), client);  // 0x17: the write happens before the read
    rsp = reply_head(req, 2 + 2 * read_n);
    append_input(static_cast<int>(read_n));
  } else if (fc == MODBUS_FC_READ_HOLDING_REGISTERS && len >= 12) {
    const unsigned addr = be16(req + 8), n = be16(req + 10);
    if (addr != 0 || n < 1 || n > 4) return bad_address();
    rsp = reply_head(req, 2 + 2 * n);
    append_input(static_cast<int>(n));
  } else if (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS && len >= 13 + 8) {
    const unsigned addr = be16(req + 8), n = be16(req + 10);
    if (addr != 0 || n != 4) return bad_address();
    drive_.write(*fhpp::decode_output(read_registers(req + 13), order), now(), client);
    rsp = reply_head(req, 5);
    put_be16(rsp, addr);
    put_be16(rsp, n);
  } else {
    return modbus_reply_exception(ctx, req, MODBUS_EXCEPTION_ILLEGAL_FUNCTION) != -1;
  }
  return ::send(fd, rsp.data(), rsp.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(rsp.size());
}

}  // namespace rangefit::sim
