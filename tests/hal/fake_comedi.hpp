// A fake Comedi library for tests: boards described as subdevices with range
// tables and per-channel values. Reads return the value the test set; writes
// store the code and append to `log`, so tests can check order and content.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "knoblab/hal/comedi_api.hpp"

namespace knoblab::hal::test {

struct FakeSubdevice {
  int type = 0;
  int flags = 0;
  unsigned n_channels = 0;
  std::uint32_t maxdata = 0;
  std::vector<ComediRange> ranges;
  std::vector<std::uint32_t> value = std::vector<std::uint32_t>(32, 0);  // per channel
};

struct FakeBoard {
  std::vector<FakeSubdevice> subdevices;
  bool reset_supported = true;
};

inline ComediRange volts(double min, double max) { return {min, max, comedi::kUnitVolt}; }

// Like a PCI-DAS1602/16: 16-bit AI (ranges as the thesis' ±1.25 V), 12-bit AO,
// an 8255 DIO and a 24-bit counter standing in for the encoder input.
inline FakeBoard das1602() {
  FakeBoard b;
  b.subdevices.push_back({comedi::kSubdeviceAnalogIn,
                          comedi::kFlagGround | comedi::kFlagCommon | comedi::kFlagDiff,
                          8,
                          65535,
                          {volts(-10, 10), volts(-5, 5), volts(-2.5, 2.5), volts(-1.25, 1.25), volts(0, 10),
                           volts(0, 5), volts(0, 2.5), volts(0, 1.25)}});
  b.subdevices.push_back({comedi::kSubdeviceAnalogOut, comedi::kFlagGround, 2, 4095,
                          {volts(-5, 5), volts(-10, 10), volts(0, 5), volts(0, 10)}});
  b.subdevices.push_back({5, 0, 24, 1, {volts(0, 5)}});  // DIO
  b.subdevices.push_back({comedi::kSubdeviceCounter, 0, 3, 0xFFFFFF, {{0, 1, 2}}});
  return b;
}

// A separate quadrature card: four 32-bit counters.
inline FakeBoard encoder_card() {
  FakeBoard b;
  b.subdevices.push_back({comedi::kSubdeviceCounter, 0, 4, 0xFFFFFFFF, {{0, 1, 2}}});
  return b;
}

class FakeComedi final : public ComediApi {
 public:
  std::map<std::string, FakeBoard> boards;
  std::vector<std::string> log;  // "open P", "close P", "write S/C=CODE", "reset S/C"
  bool fail_reads = false;
  bool fail_writes = false;
  int open_devices = 0;

  FakeSubdevice& sub(const std::string& path, unsigned s) { return boards.at(path).subdevices.at(s); }
  void set(const std::string& path, unsigned s, unsigned ch, std::uint32_t v) { sub(path, s).value.at(ch) = v; }
  std::uint32_t get(const std::string& path, unsigned s, unsigned ch) { return sub(path, s).value.at(ch); }

  ComediDevice* open(const char* path) override {
    const auto it = boards.find(path);
    if (it == boards.end()) return fail_with("No such file or directory"), nullptr;
    ++open_devices;
    log.push_back("open " + it->first);
    return reinterpret_cast<ComediDevice*>(&*it);
  }
  void close(ComediDevice* dev) override {
    --open_devices;
    log.push_back("close " + entry(dev).first);
  }
  std::string last_error() override { return error_; }

  int n_subdevices(ComediDevice* dev) override { return static_cast<int>(board(dev).subdevices.size()); }
  int subdevice_type(ComediDevice* dev, unsigned s) override { return s_ok(dev, s) ? subdev(dev, s).type : -1; }
  int subdevice_flags(ComediDevice* dev, unsigned s) override { return s_ok(dev, s) ? subdev(dev, s).flags : -1; }
  int find_subdevice_by_type(ComediDevice* dev, int type, unsigned start) override {
    for (unsigned s = start; s < board(dev).subdevices.size(); ++s)
      if (subdev(dev, s).type == type) return static_cast<int>(s);
    return fail_with("Invalid argument"), -1;
  }
  int n_channels(ComediDevice* dev, unsigned s) override {
    return s_ok(dev, s) ? static_cast<int>(subdev(dev, s).n_channels) : -1;
  }
  int n_ranges(ComediDevice* dev, unsigned s, unsigned ch) override {
    return ch_ok(dev, s, ch) ? static_cast<int>(subdev(dev, s).ranges.size()) : -1;
  }
  bool get_range(ComediDevice* dev, unsigned s, unsigned ch, unsigned r, ComediRange& out) override {
    if (!ch_ok(dev, s, ch) || r >= subdev(dev, s).ranges.size()) return fail_with("Invalid argument"), false;
    out = subdev(dev, s).ranges[r];
    return true;
  }
  std::uint32_t maxdata(ComediDevice* dev, unsigned s, unsigned ch) override {
    return ch_ok(dev, s, ch) ? subdev(dev, s).maxdata : 0;
  }
  bool reset_counter(ComediDevice* dev, unsigned s, unsigned ch) override {
    if (!ch_ok(dev, s, ch) || !board(dev).reset_supported) return fail_with("Invalid argument"), false;
    log.push_back("reset " + std::to_string(s) + "/" + std::to_string(ch));
    subdev(dev, s).value[ch] = 0;
    return true;
  }
  bool data_read(ComediDevice* dev, unsigned s, unsigned ch, unsigned, unsigned, std::uint32_t& data) override {
    if (fail_reads || !ch_ok(dev, s, ch)) return fail_with("Input/output error"), false;
    data = subdev(dev, s).value[ch];
    return true;
  }
  bool data_write(ComediDevice* dev, unsigned s, unsigned ch, unsigned, unsigned, std::uint32_t data) override {
    if (fail_writes || !ch_ok(dev, s, ch)) return fail_with("Input/output error"), false;
    subdev(dev, s).value[ch] = data;
    log.push_back("write " + std::to_string(s) + "/" + std::to_string(ch) + "=" + std::to_string(data));
    return true;
  }

 private:
  using Entry = std::pair<const std::string, FakeBoard>;
  static Entry& entry(ComediDevice* dev) { return *reinterpret_cast<Entry*>(dev); }
  static FakeBoard& board(ComediDevice* dev) { return entry(dev).second; }
  static FakeSubdevice& subdev(ComediDevice* dev, unsigned s) { return board(dev).subdevices[s]; }
  bool s_ok(ComediDevice* dev, unsigned s) {
    return s < board(dev).subdevices.size() || (fail_with("Invalid argument"), false);
  }
  bool ch_ok(ComediDevice* dev, unsigned s, unsigned ch) {
    return (s_ok(dev, s) && ch < subdev(dev, s).n_channels) || (fail_with("Invalid argument"), false);
  }
  void fail_with(const char* why) { error_ = why; }

  std::string error_ = "Success";
};

}  // namespace knoblab::hal::test
