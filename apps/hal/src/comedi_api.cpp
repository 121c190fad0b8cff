// The real ComediApi: thin forwarding to comedilib. The only file that sees
// <comedilib.h>, so the rest of the HAL and its tests stay board-agnostic.
#include <comedilib.h>

#include "knoblab/hal/comedi_api.hpp"

namespace knoblab::hal {

static_assert(comedi::kSubdeviceAnalogIn == COMEDI_SUBD_AI);
static_assert(comedi::kSubdeviceAnalogOut == COMEDI_SUBD_AO);
static_assert(comedi::kSubdeviceCounter == COMEDI_SUBD_COUNTER);
static_assert(comedi::kUnitVolt == UNIT_volt && comedi::kRangeExternal == RF_EXTERNAL);
static_assert(comedi::kArefGround == AREF_GROUND && comedi::kArefCommon == AREF_COMMON &&
              comedi::kArefDiff == AREF_DIFF && comedi::kArefOther == AREF_OTHER);
static_assert(comedi::kFlagGround == SDF_GROUND && comedi::kFlagCommon == SDF_COMMON &&
              comedi::kFlagDiff == SDF_DIFF && comedi::kFlagOther == SDF_OTHER);
static_assert(sizeof(lsampl_t) == sizeof(std::uint32_t));

namespace {

comedi_t* raw(ComediDevice* dev) { return reinterpret_cast<comedi_t*>(dev); }

class SystemComediApi final : public ComediApi {
 public:
  ComediDevice* open(const char* path) override { return reinterpret_cast<ComediDevice*>(comedi_open(path)); }
  void close(ComediDevice* dev) override { comedi_close(raw(dev)); }
  std::string last_error() override { return comedi_strerror(comedi_errno()); }

  int n_subdevices(ComediDevice* dev) override { return comedi_get_n_subdevices(raw(dev)); }
  int subdevice_type(ComediDevice* dev, unsigned subdevice) override {
    return comedi_get_subdevice_type(raw(dev), subdevice);
  }
  int subdevice_flags(ComediDevice* dev, unsigned subdevice) override {
    return comedi_get_subdevice_flags(raw(dev), subdevice);
  }
  int find_subdevice_by_type(ComediDevice* dev, int type, unsigned start) override {
    return comedi_find_subdevice_by_type(raw(dev), type, start);
  }
  int n_channels(ComediDevice* dev, unsigned subdevice) override {
    return comedi_get_n_channels(raw(dev), subdevice);
  }
  int n_ranges(ComediDevice* dev, unsigned subdevice, unsigned channel) override {
    return comedi_get_n_ranges(raw(dev), subdevice, channel);
  }
  bool get_range(ComediDevice* dev, unsigned subdevice, unsigned channel, unsigned range,
                 ComediRange& out) override {
    const comedi_range* r = comedi_get_range(raw(dev), subdevice, channel, range);
    if (r == nullptr) return false;
    out = {r->min, r->max, r->unit};
    return true;
  }
  std::uint32_t maxdata(ComediDevice* dev, unsigned subdevice, unsigned channel) override {
    return comedi_get_maxdata(raw(dev), subdevice, channel);
  }
  bool reset_counter(ComediDevice* dev, unsigned subdevice, unsigned channel) override {
    lsampl_t data[1] = {INSN_CONFIG_RESET};
    comedi_insn insn{};
    insn.insn = INSN_CONFIG;
    insn.n = 1;
    insn.data = data;
    insn.subdev = subdevice;
    insn.chanspec = CR_PACK(channel, 0, 0);
    return comedi_do_insn(raw(dev), &insn) >= 0;
  }
  bool data_read(ComediDevice* dev, unsigned subdevice, unsigned channel, unsigned range, unsigned aref,
                 std::uint32_t& data) override {
    lsampl_t value = 0;
    const bool ok = comedi_data_read(raw(dev), subdevice, channel, range, aref, &value) >= 0;
    data = value;
    return ok;
  }
  bool data_write(ComediDevice* dev, unsigned subdevice, unsigned channel, unsigned range, unsigned aref,
                  std::uint32_t data) override {
    return comedi_data_write(raw(dev), subdevice, channel, range, aref, data) >= 0;
  }
};

}  // namespace

ComediApi& system_comedi_api() {
  static SystemComediApi api;
  return api;
}

}  // namespace knoblab::hal
