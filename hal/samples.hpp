#pragma once
// Raw samples as they leave a device, before fusion. Every field states its unit; every sample
// carries a CLOCK_MONOTONIC stamp taken as close to the hardware as the driver can.

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "hal/time.hpp"

namespace rangefit::hal {

inline constexpr float kNoReturn = std::numeric_limits<float>::quiet_NaN();

// One beam revolution of the Circular Scanning Sensor (thesis 4.2.1): 512 samples, equally spaced
// in beam angle, sample i at angle phase_rad + 2*pi*i/512 in the sensor frame.
struct CssRevolution {
  static constexpr int kSamples = 512;
  std::uint32_t sequence = 0;   // device revolution counter; gaps mean lost revolutions
  Timestamp stamp{};            // index pulse (sample 0), host CLOCK_MONOTONIC
  Duration period{};            // revolution period as measured by the device (~1/7 s)
  std::uint16_t flags = 0;      // CssFlags bits
  std::array<float, kSamples> range_mm{};      // distance along the beam, mm; NaN = no return
  std::array<std::uint8_t, kSamples> intensity{};
  std::array<std::uint8_t, kSamples> quality{};
};

enum CssFlags : std::uint16_t {
  kCssMotorLocked = 1u << 0,
  kCssLaserOn = 1u << 1,
  kCssOverTemperature = 1u << 2,
  kCssSaturation = 1u << 3,
};

// One robot or pan-tilt joint position (CiA 402 TPDO, PowerCube reply, or simulator).
struct JointSample {
  std::uint8_t joint = 0;       // joint id as configured (e.g. 6 = robot's last joint)
  Timestamp stamp{};            // sampling instant (SYNC echo or reply), host CLOCK_MONOTONIC
  double angle_rad = 0.0;       // rad
  double velocity_rad_s = 0.0;  // rad/s; 0 when the device does not report it
  std::uint16_t status = 0;     // device status word (CiA 402 statusword / PowerCube state)
  bool valid = true;            // false when the device flagged the value (fault, not homed)
};

// One profile of the laser-stripe ranger: points along the laser line in the ranger's frame.
struct RangerProfile {
  std::uint32_t sequence = 0;   // device profile counter
  Timestamp stamp{};            // exposure centre, host CLOCK_MONOTONIC
  Duration exposure{};          // exposure time
  std::uint16_t flags = 0;      // RangerFlags bits
  // Point k: lateral coordinate x_mm[k] along the laser line, range z_mm[k] in the laser plane,
  // both in the ranger frame, mm. NaN z = no return (shadow, out of range).
  std::vector<float> x_mm;
  std::vector<float> z_mm;
};

enum RangerFlags : std::uint16_t {
  kRangerOverrun = 1u << 0,
  kRangerSaturated = 1u << 1,
  kRangerLaserOff = 1u << 2,
};

// Position of the linear axis that carries objects through the stripe sensor's plane.
struct AxisSample {
  Timestamp stamp{};            // midpoint of request and reply, host CLOCK_MONOTONIC
  Duration uncertainty{};       // request/reply round trip; the stamp is within +-uncertainty/2
  double position_mm = 0.0;     // mm along the axis from its reference point
  double velocity_mm_s = 0.0;   // mm/s as reported by the drive
  std::uint8_t scon = 0;        // FHPP status bytes, for diagnostics
  std::uint8_t spos = 0;
  bool valid = true;            // false when round trip over limit or implausible
};

// Pan and tilt angles of the mobile scanning head (thesis eq. 5.7-5.10).
struct PanTiltSample {
  Timestamp stamp{};
  double pan_rad = 0.0;
  double tilt_rad = 0.0;
  bool valid = true;
};

}  // namespace rangefit::hal
