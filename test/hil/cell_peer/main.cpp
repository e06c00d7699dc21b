// rangefit_cell_peer: the device side of a simulated cell on the real transports, for running
// rangefitd with driver = "real" devices in the HIL VM. The CSS cell: the sensor as a USB gadget
// (FunctionFS on dummy_hcd) streaming revolutions cast by the simulated cell (sim::CssRig over a
// scene, recorded on the host by --record) while the robot's last joint, a CiA 402 node on a
// SocketCAN interface, answers every SYNC with the angle of the same sweep (test/hil/cell_peer/
// css_sweep.hpp: -delta .. +delta in scan_s, back with the laser off, again). With --stripe, the
// stripe cell too (stripe_cell.hpp): the linear axis' Festo drive as a Modbus TCP server on
// 127.0.0.1:--modbus-port and the laser-stripe ranger on the same CAN bus (node --ranger-node),
// its profiles those the simulated cell casts at the table's position (recorded on the host by
// --record-stripe); with --stripe-b, a second camera of the laser plane on the other side (its
// ranger node --ranger-b-node, silent until camera-b-on; recorded with --stripe-baseline -300).
// With --pan-tilt, the pan-tilt head too (pan_tilt_head.hpp): its pan and
// tilt axes (CiA 402 nodes --pan-node, --tilt-node) and its ranger (CAN FD, --head-ranger-node)
// on their own bus --head-can, the head panning +-(--pan-half-deg) about zero in --head-sweep-s
// and back, for ever; the profiles those the simulated head casts at each pan (recorded on the
// host by --record-pan-tilt); with --pan-tilt-b, a second camera of the head's laser plane on the
// other side (its ranger node --head-ranger-b-node on the same bus, silent until
// head-camera-b-on; recorded with --head-baseline -425). Needs root, vcan and the gadget modules
// (test/hil/run_vm.sh).
//   rangefit_cell_peer --frames FILE [--can vcan0] [--node 1] [--scan-s 6] [--vid 0x1d6b]
//                      [--pid 0x0105] [--udc NAME]
//                      [--stripe FILE.profiles [--modbus-port 1502] [--ranger-node 0x20]
//                       [--stripe-b FILE.profiles [--ranger-b-node 0x21]]]
//                      [--pan-tilt FILE.profiles [--head-can vcan1] [--pan-node 1]
//                       [--tilt-node 2] [--head-ranger-node 0x20] [--head-rate-hz 25]
//                       [--pan-half-deg 10] [--head-sweep-s 4]
//                       [--pan-tilt-b FILE.profiles [--head-ranger-b-node 0x21]]]
//   rangefit_cell_peer --record FILE --scene bore_plate.toml [--scan-s 6]   (host, no root)
//   rangefit_cell_peer --record-stripe FILE.profiles --scene table_top_fig5_18.toml
//                      [--stripe-baseline 300]   (host)
//   rangefit_cell_peer --record-pan-tilt FILE.profiles --scene table_top_fig5_18.toml
//                      [--pan-half-deg 10] [--head-points 512] [--head-baseline 425]   (host)
// Then one command per line on stdin: unplug, replug (the CSS), axis-stop, axis-start,
// axis-stop-past MM (the stripe cell's Modbus server; the last stops it once the table passes MM
// moving up), tilt-stop, tilt-start, tilt-stop-mid-stroke (the head's tilt axis stops answering;
// the last once the pan passes zero on a forward stroke), head-off, head-on (the whole head
// switched off: its devices silent), camera-b-on, camera-b-off (the stripe cell's second camera),
// head-camera-b-on, head-camera-b-off (the head's second camera), status, quit (or end of input).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>

#include "drivers/can/socketcan_transport.hpp"
#include "test/hil/cell_peer/css_sweep.hpp"
#include "test/hil/cell_peer/pan_tilt_head.hpp"
#include "test/hil/cell_peer/stripe_cell.hpp"
#include "test/hil/css_gadget/css_gadget.hpp"
#include "test/support/can_bus.hpp"
#include "test/support/can_cia402_node.hpp"

namespace {

using namespace rangefit;

constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;

int usage(const std::string& why) {
  std::fprintf(stderr, "rangefit_cell_peer: %s\n(see test/hil/cell_peer/main.cpp)\n", why.c_str());
  return 2;
}

struct Args {
  std::string frames, record, scene, can = "vcan0", udc, stripe, stripe_b, record_stripe;
  std::string pan_tilt, pan_tilt_b, record_pan_tilt, head_can = "vcan1";
  double scan_s = 6.0, head_rate_hz = 25.0, pan_half_deg = 10.0, head_sweep_s = 4.0;
  int head_points = 512;  // the head's ranger (hal::PanTiltGeometry)
  unsigned node = 1, vid = 0x1d6b, pid = 0x0105, ranger_node = 0x20, ranger_b_node = 0x21;
  double stripe_baseline_mm = hal::StripeCellGeometry{}.ranger.baseline_mm;
  unsigned pan_node = 1, tilt_node = 2, head_ranger_node = 0x20, head_ranger_b_node = 0x21;
  double head_baseline_mm = hal::PanTiltGeometry{}.ranger.baseline_mm;
  int modbus_port = 1502;
};

bool parse(int argc, char** argv, Args& a, std::string& why) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) {
      why = "missing value after " + arg;
      return false;
    }
    const std::string v = argv[++i];
    if (arg == "--frames") {
      a.frames = v;
    } else if (arg == "--record") {
      a.record = v;
    } else if (arg == "--stripe") {
      a.stripe = v;
    } else if (arg == "--record-stripe") {
      a.record_stripe = v;
    } else if (arg == "--stripe-b") {
      a.stripe_b = v;
    } else if (arg == "--ranger-b-node") {
      a.ranger_b_node = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 0));
    } else if (arg == "--stripe-baseline") {
      a.stripe_baseline_mm = std::strtod(v.c_str(), nullptr);
    } else if (arg == "--modbus-port") {
      a.modbus_port = std::atoi(v.c_str());
    } else if (arg == "--ranger-node") {
      a.ranger_node = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 0));
    } else if (arg == "--pan-tilt") {
      a.pan_tilt = v;
    } else if (arg == "--pan-tilt-b") {
      a.pan_tilt_b = v;
    } else if (arg == "--head-ranger-b-node") {
      a.head_ranger_b_node = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 0));
    } else if (arg == "--head-baseline") {
      a.head_baseline_mm = std::strtod(v.c_str(), nullptr);
    } else if (arg == "--record-pan-tilt") {
      a.record_pan_tilt = v;
    } else if (arg == "--head-can") {
      a.head_can = v;
    } else if (arg == "--pan-node") {
      a.pan_node = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 0));
    } else if (arg == "--tilt-node") {
      a.tilt_node = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 0));
    } else if (arg == "--head-ranger-node") {
      a.head_ranger_node = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 0));
    } else if (arg == "--head-points") {
      a.head_points = std::atoi(v.c_str());
    } else if (arg == "--head-rate-hz") {
      a.head_rate_hz = std::strtod(v.c_str(), nullptr);
    } else if (arg == "--pan-half-deg") {
      a.pan_half_deg = std::strtod(v.c_str(), nullptr);
    } else if (arg == "--head-sweep-s") {
      a.head_sweep_s = std::strtod(v.c_str(), nullptr);
    } else if (arg == "--scene") {
      a.scene = v;
    } else if (arg == "--can") {
      a.can = v;
    } else if (arg == "--udc") {
      a.udc = v;
    } else if (arg == "--scan-s") {
      a.scan_s = std::strtod(v.c_str(), nullptr);
    } else if (arg == "--node") {
      a.node = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 0));
    } else if (arg == "--vid") {
      a.vid = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 0));
    } else if (arg == "--pid") {
      a.pid = static_cast<unsigned>(std::strtoul(v.c_str(), nullptr, 0));
    } else {
      why = "unknown option " + arg;
      return false;
    }
  }
  if (!(a.scan_s >= 1.0 && a.scan_s <= 60.0)) why = "--scan-s must be within 1..60";
  if (a.node < 1 || a.node > 127) why = "--node must be within 1..127";
  if (a.ranger_node < 1 || a.ranger_node > 127) why = "--ranger-node must be within 1..127";
  if (a.ranger_b_node < 1 || a.ranger_b_node > 127 || a.ranger_b_node == a.ranger_node) {
    why = "--ranger-b-node must be within 1..127 and differ from --ranger-node";
  }
  if (!std::isfinite(a.stripe_baseline_mm) || a.stripe_baseline_mm == 0.0) {
    why = "--stripe-baseline must be a non-zero number of mm";
  }
  if (a.modbus_port < 1 || a.modbus_port > 65535) why = "--modbus-port must be within 1..65535";
  for (const unsigned n : {a.pan_node, a.tilt_node, a.head_ranger_node, a.head_ranger_b_node}) {
    if (n < 1 || n > 127) {
      why =
          "--pan-node, --tilt-node, --head-ranger-node, --head-ranger-b-node must be within 1..127";
    }
  }
  if (a.pan_node == a.tilt_node || a.pan_node == a.head_ranger_node ||
      a.tilt_node == a.head_ranger_node ||
      (!a.pan_tilt_b.empty() &&
       (a.head_ranger_b_node == a.pan_node || a.head_ranger_b_node == a.tilt_node ||
        a.head_ranger_b_node == a.head_ranger_node))) {
    why = "the head's pan, tilt and ranger nodes (and its second camera's) must differ";
  }
  if (!std::isfinite(a.head_baseline_mm) || a.head_baseline_mm == 0.0) {
    why = "--head-baseline must be a non-zero number of mm";
  }
  if (a.head_points < 2 || a.head_points > 527) why = "--head-points must be within 2..527";
  if (!(a.head_rate_hz >= 1.0 && a.head_rate_hz <= 200.0)) why = "--head-rate-hz must be 1..200";
  if (!(a.pan_half_deg > 0.0 && a.pan_half_deg <= 60.0)) why = "--pan-half-deg must be 0..60";
  if (!(a.head_sweep_s >= 0.5 && a.head_sweep_s <= 60.0)) why = "--head-sweep-s must be 0.5..60";
  if (a.record.empty() && a.record_stripe.empty() && a.record_pan_tilt.empty() &&
      a.frames.empty()) {
    why = "--frames, --record, --record-stripe or --record-pan-tilt is required";
  }
  return why.empty();
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (std::string why; !parse(argc, argv, a, why)) return usage(why);
  if (!a.record.empty()) {
    if (a.scene.empty()) return usage("--record needs --scene");
    const hil::RevolutionSource cast(a.scene, a.scan_s);
    if (!cast.error().empty()) return usage(cast.error());
    if (!cast.save(a.record)) return usage("cannot write " + a.record);
    std::printf("rangefit_cell_peer: %zu revolutions of %s in %s\n", cast.size(), a.scene.c_str(),
                a.record.c_str());
    return 0;
  }
  if (!a.record_stripe.empty()) {
    if (a.scene.empty()) return usage("--record-stripe needs --scene");
    hal::StripeCellGeometry cell;
    cell.ranger.baseline_mm = a.stripe_baseline_mm;
    const hil::StripeProfiles cast(a.scene, hil::stripe_cell_sweep(cell));
    if (!cast.error().empty()) return usage(cast.error());
    if (!cast.save(a.record_stripe)) return usage("cannot write " + a.record_stripe);
    std::printf("rangefit_cell_peer: %zu stripe profiles of %s in %s\n", cast.size(),
                a.scene.c_str(), a.record_stripe.c_str());
    return 0;
  }
  if (!a.record_pan_tilt.empty()) {
    if (a.scene.empty()) return usage("--record-pan-tilt needs --scene");
    hal::PanTiltGeometry head;
    head.ranger.points_per_profile = a.head_points;
    head.ranger.baseline_mm = a.head_baseline_mm;
    const hil::StripeProfiles cast(a.scene, hil::pan_tilt_sweep(head, a.pan_half_deg * kRadPerDeg));
    if (!cast.error().empty()) return usage(cast.error());
    if (!cast.save(a.record_pan_tilt)) return usage("cannot write " + a.record_pan_tilt);
    std::printf("rangefit_cell_peer: %zu pan-tilt profiles of %s in %s\n", cast.size(),
                a.scene.c_str(), a.record_pan_tilt.c_str());
    return 0;
  }
  const hil::RevolutionSource forward(a.frames);
  if (!forward.error().empty()) return usage(forward.error());
  hil::CssSweepOptions so;
  so.scan_s = a.scan_s;
  // The first stroke starts a second from now: the service has time to come up and connect.
  const hil::CssSweep sweep(forward, so, hal::monotonic_now() + std::chrono::seconds(1));

  drivers::can::SocketCanConfig cc;
  cc.interface = a.can;
  cc.fd = !a.stripe.empty();  // the ranger's profiles are CAN FD frames
  auto transport = std::make_unique<drivers::can::SocketCanTransport>(cc);
  if (const hal::Status s = transport->open(); !s) return usage(a.can + ": " + s.message);
  sim::SimCanBus bus(std::move(transport));
  sim::SimCia402Config jc;
  jc.node = static_cast<std::uint8_t>(a.node);
  bus.add(std::make_shared<sim::SimCia402Node>(
      jc, [&sweep](hal::Timestamp t) { return sweep.omega_at(t); }));
  std::unique_ptr<hil::StripeProfiles> profiles, profiles_b;
  std::unique_ptr<hil::StripeCellPeer> stripe;
  if (!a.stripe.empty()) {
    profiles = std::make_unique<hil::StripeProfiles>(a.stripe);
    if (!profiles->error().empty()) return usage(profiles->error());
    if (!a.stripe_b.empty()) {
      profiles_b = std::make_unique<hil::StripeProfiles>(a.stripe_b);
      if (!profiles_b->error().empty()) return usage(profiles_b->error());
    }
    stripe = std::make_unique<hil::StripeCellPeer>(
        *profiles,
        hil::StripeCellPeerOptions{
            .modbus_port = a.modbus_port,
            .ranger_node = static_cast<std::uint8_t>(a.ranger_node),
            .second_ranger_node = static_cast<std::uint8_t>(a.ranger_b_node)},
        profiles_b.get());
    if (const hal::Status s = stripe->start_axis(); !s) return usage(s.message);
    bus.add(stripe->ranger());
    if (stripe->second_ranger()) bus.add(stripe->second_ranger());
  }
  // The head on its own bus: its driver is that bus' SYNC master, as the robot joint's is vcan0's.
  std::unique_ptr<hil::StripeProfiles> head_profiles, head_profiles_b;
  std::unique_ptr<hil::PanTiltHeadPeer> head;
  std::unique_ptr<sim::SimCanBus> head_bus;
  if (!a.pan_tilt.empty()) {
    head_profiles = std::make_unique<hil::StripeProfiles>(a.pan_tilt);
    if (!head_profiles->error().empty()) return usage(head_profiles->error());
    if (!a.pan_tilt_b.empty()) {
      head_profiles_b = std::make_unique<hil::StripeProfiles>(a.pan_tilt_b);
      if (!head_profiles_b->error().empty()) return usage(head_profiles_b->error());
    }
    hil::PanTiltHeadOptions ho;
    ho.pan_node = static_cast<std::uint8_t>(a.pan_node);
    ho.tilt_node = static_cast<std::uint8_t>(a.tilt_node);
    ho.ranger_node = static_cast<std::uint8_t>(a.head_ranger_node);
    ho.second_ranger_node = static_cast<std::uint8_t>(a.head_ranger_b_node);
    ho.profile_rate_hz = a.head_rate_hz;
    ho.sweep.half_rad = a.pan_half_deg * kRadPerDeg;
    ho.sweep.forward_s = a.head_sweep_s;
    head = std::make_unique<hil::PanTiltHeadPeer>(
        *head_profiles, ho, hal::monotonic_now() + std::chrono::seconds(1), head_profiles_b.get());
    drivers::can::SocketCanConfig hc;
    hc.interface = a.head_can;
    hc.fd = true;
    auto head_transport = std::make_unique<drivers::can::SocketCanTransport>(hc);
    if (const hal::Status s = head_transport->open(); !s)
      return usage(a.head_can + ": " + s.message);
    head_bus = std::make_unique<sim::SimCanBus>(std::move(head_transport));
    head->add_to(*head_bus);
    head_bus->start();
  }
  bus.start();

  hil::CssGadgetOptions go;
  go.vendor_id = static_cast<std::uint16_t>(a.vid);
  go.product_id = static_cast<std::uint16_t>(a.pid);
  go.udc = a.udc;
  go.pulse_origin = sweep.origin();
  go.revolution = [&sweep](std::uint64_t j, auto& samples) { return sweep.revolution(j, samples); };
  hil::CssGadget gadget(go);
  if (const std::string e = gadget.start(); !e.empty()) return usage(e);
  std::printf(
      "rangefit_cell_peer: css cell up: %zu revolutions per %.1f s stroke, cycle %.2f s, "
      "joint node %u on %s\n",
      forward.size(), a.scan_s, sweep.cycle_s(), a.node, a.can.c_str());
  if (stripe) {
    std::printf(
        "rangefit_cell_peer: stripe cell up: %zu profiles, axis on 127.0.0.1:%d, ranger "
        "node %u on %s\n",
        profiles->size(), a.modbus_port, a.ranger_node, a.can.c_str());
  }
  if (head) {
    const std::string second =
        head->has_second_camera()
            ? ", second camera's ranger node " + std::to_string(a.head_ranger_b_node) + " (off)"
            : "";
    std::printf(
        "rangefit_cell_peer: pan-tilt head up: %zu profiles, pan +-%.1f deg in %.1f s (cycle "
        "%.1f s), pan node %u, tilt node %u, ranger node %u%s on %s\n",
        head_profiles->size(), a.pan_half_deg, a.head_sweep_s, head->cycle_s(), a.pan_node,
        a.tilt_node, a.head_ranger_node, second.c_str(), a.head_can.c_str());
  }
  std::fflush(stdout);
  for (std::string line; std::getline(std::cin, line) && line != "quit";) {
    if (line == "unplug") {
      gadget.unplug();
    } else if (line == "replug") {
      gadget.replug();
    } else if (stripe && line == "axis-stop") {
      stripe->stop_axis();
    } else if (stripe && line.starts_with("axis-stop-past ")) {
      stripe->stop_axis_past(std::strtod(line.c_str() + 15, nullptr));
    } else if (stripe && line == "axis-start") {
      if (const hal::Status s = stripe->start_axis(); !s) {
        std::fprintf(stderr, "rangefit_cell_peer: %s\n", s.message.c_str());
      }
    } else if (stripe && (line == "camera-b-on" || line == "camera-b-off")) {
      stripe->set_second_camera_on(line == "camera-b-on");
    } else if (head && line == "tilt-stop") {
      head->set_tilt_silent(true);
    } else if (head && line == "tilt-start") {
      head->set_tilt_silent(false);
    } else if (head && (line == "head-off" || line == "head-on")) {
      head->set_powered(line == "head-on");
    } else if (head && line == "tilt-stop-mid-stroke") {
      head->stop_tilt_mid_stroke();
    } else if (head && (line == "head-camera-b-on" || line == "head-camera-b-off")) {
      head->set_second_camera_on(line == "head-camera-b-on");
    } else if (line != "status") {
      std::fprintf(stderr, "rangefit_cell_peer: unknown command %s\n", line.c_str());
    }
    std::printf("frames %llu streaming %d starts %llu",
                static_cast<unsigned long long>(gadget.frames_sent()), gadget.streaming() ? 1 : 0,
                static_cast<unsigned long long>(gadget.starts()));
    if (stripe) {
      std::printf(" profiles %llu axis %.3f mm%s%s",
                  static_cast<unsigned long long>(stripe->profiles_sent()), stripe->position_mm(),
                  stripe->axis_up() ? "" : " server-down", stripe->axis_fault() ? " fault" : "");
      if (stripe->second_ranger()) {
        std::printf(" camera-b %s", stripe->second_camera_on() ? "on" : "off");
      }
    }
    if (head) {
      std::printf(" head profiles %llu syncs %llu%s%s",
                  static_cast<unsigned long long>(head->profiles_sent()),
                  static_cast<unsigned long long>(head->syncs_answered()),
                  head->tilt_silent() ? " tilt-silent" : "", head->powered() ? "" : " off");
      if (head->has_second_camera()) {
        std::printf(" head-camera-b %s", head->second_camera_on() ? "on" : "off");
      }
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  if (head_bus) head_bus->stop();
  bus.stop();
  return 0;
}
