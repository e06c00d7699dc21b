#include "test/support/can_powercube_module.hpp"

namespace rangefit::sim {

void SimPowerCubeModule::on_frame(const drivers::can::CanFrame& f,
                                  drivers::can::CanTransport& bus) {
  using namespace drivers::can::powercube;  // NOLINT: codec names read better unqualified here
  const Message m = decode(f);
  if (m.kind != Kind::kPositionRequest || m.module != module_) return;
  ++requests_;
  if (silent_) return;
  PositionReply r;
  r.module = module_;
  r.position_rad = static_cast<float>(angle_ ? angle_(f.stamp) : angle_value_.load());
  r.state = static_cast<std::uint8_t>(kStateRampEnd | kStateHome * 0 | (not_ok_ ? kStateNotOk : 0));
  drivers::can::CanFrame reply = encode_position_reply(r);
  if (short_reply_.exchange(false)) reply.len = 6;
  (void)bus.send(reply);
}

}  // namespace rangefit::sim
