// The few comedilib calls ComediDaq makes, behind an interface so tests can
// swap in a fake board. system_comedi_api() is the real library; only
// src/comedi_api.cpp includes <comedilib.h>. Return conventions follow
// comedilib (negative / nullptr / 0 on failure, then last_error() says why).
#pragma once

#include <cstdint>
#include <string>

namespace knoblab::hal {

struct ComediDevice;  // opaque: comedi_t in the real API

struct ComediRange {
  double min = 0.0;
  double max = 0.0;
  unsigned unit = 0;  // comedi UNIT_* (| RF_EXTERNAL)
};

// Values from <comedi.h>, mirrored (and static_asserted in comedi_api.cpp)
// so that callers and fakes need not include it.
namespace comedi {
inline constexpr int kSubdeviceAnalogIn = 1;   // COMEDI_SUBD_AI
inline constexpr int kSubdeviceAnalogOut = 2;  // COMEDI_SUBD_AO
inline constexpr int kSubdeviceCounter = 6;    // COMEDI_SUBD_COUNTER
inline constexpr unsigned kUnitVolt = 0;           // UNIT_volt
inline constexpr unsigned kRangeExternal = 0x100;  // RF_EXTERNAL
inline constexpr unsigned kArefGround = 0, kArefCommon = 1, kArefDiff = 2, kArefOther = 3;
inline constexpr int kFlagGround = 0x00100000;  // SDF_GROUND
inline constexpr int kFlagCommon = 0x00200000;  // SDF_COMMON
inline constexpr int kFlagDiff = 0x00400000;    // SDF_DIFF
inline constexpr int kFlagOther = 0x00800000;   // SDF_OTHER
}  // namespace comedi

class ComediApi {
 public:
  virtual ~ComediApi() = default;

  virtual ComediDevice* open(const char* path) = 0;
  virtual void close(ComediDevice* dev) = 0;
  virtual std::string last_error() = 0;  // why the last call failed (setup time only)

  virtual int n_subdevices(ComediDevice* dev) = 0;
  virtual int subdevice_type(ComediDevice* dev, unsigned subdevice) = 0;
  virtual int subdevice_flags(ComediDevice* dev, unsigned subdevice) = 0;
  virtual int find_subdevice_by_type(ComediDevice* dev, int type, unsigned start) = 0;
  virtual int n_channels(ComediDevice* dev, unsigned subdevice) = 0;
  virtual int n_ranges(ComediDevice* dev, unsigned subdevice, unsigned channel) = 0;
  virtual bool get_range(ComediDevice* dev, unsigned subdevice, unsigned channel, unsigned range,
                         ComediRange& out) = 0;
  virtual std::uint32_t maxdata(ComediDevice* dev, unsigned subdevice, unsigned channel) = 0;
  // INSN_CONFIG_RESET on a counter channel (zeroes it on most drivers).
  virtual bool reset_counter(ComediDevice* dev, unsigned subdevice, unsigned channel) = 0;

  // The realtime pair: one synchronous instruction each, no allocation.
  virtual bool data_read(ComediDevice* dev, unsigned subdevice, unsigned channel, unsigned range,
                         unsigned aref, std::uint32_t& data) = 0;
  virtual bool data_write(ComediDevice* dev, unsigned subdevice, unsigned channel, unsigned range,
                          unsigned aref, std::uint32_t data) = 0;
};

// comedilib itself; a process-wide stateless instance.
ComediApi& system_comedi_api();

}  // namespace knoblab::hal
