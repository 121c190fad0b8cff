#include "knoblab/hal/gpiod_lines.hpp"

#include <fcntl.h>

#include <cerrno>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>

#include "gpiod_handles.hpp"

namespace knoblab::hal {

namespace {

using detail::GpiodPtr;

constexpr std::size_t kEventCapacity = 16;  // per poll; presses come from seqno, so overflow is harmless

gpiod_line_bias to_gpiod(Bias bias) {
  switch (bias) {
    case Bias::AsIs: return GPIOD_LINE_BIAS_AS_IS;
    case Bias::Disabled: return GPIOD_LINE_BIAS_DISABLED;
    case Bias::PullUp: return GPIOD_LINE_BIAS_PULL_UP;
    case Bias::PullDown: return GPIOD_LINE_BIAS_PULL_DOWN;
  }
  return GPIOD_LINE_BIAS_AS_IS;
}

template <class T>
T* checked(T* p) {
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

std::string describe(const LineSpec& spec, LineRole role, const LineLocation& at) {
  return "GPIO line \"" + spec.name + "\" (" + std::string(role_key(role)) + ", " + at.chip + " offset " +
         std::to_string(at.offset) + ")";
}

// Who holds the line, when a request fails with EBUSY.
std::string holder(gpiod_chip* chip, unsigned offset) {
  GpiodPtr<gpiod_line_info> info(gpiod_chip_get_line_info(chip, offset));
  const char* consumer = info ? gpiod_line_info_get_consumer(info.get()) : nullptr;
  return consumer ? " (in use by \"" + std::string(consumer) + "\")" : std::string();
}

gpiod_line_request* request_line(const LineLocation& at, const LineSpec& spec, LineRole role,
                                 const std::string& consumer) {
  GpiodPtr<gpiod_chip> chip(gpiod_chip_open(at.chip.c_str()));
  if (!chip) throw std::runtime_error(chip_open_error(at.chip, errno));

  GpiodPtr<gpiod_line_settings> settings(checked(gpiod_line_settings_new()));
  gpiod_line_settings* s = settings.get();
  gpiod_line_settings_set_active_low(s, spec.active_low);
  if (is_output(role)) {
    gpiod_line_settings_set_direction(s, GPIOD_LINE_DIRECTION_OUTPUT);
    gpiod_line_settings_set_output_value(s, GPIOD_LINE_VALUE_INACTIVE);  // amp disabled, LED off
  } else {
    gpiod_line_settings_set_direction(s, GPIOD_LINE_DIRECTION_INPUT);
    gpiod_line_settings_set_bias(s, to_gpiod(spec.bias));
  }
  if (role == LineRole::CaptureButton)  // logical rising = press (the kernel honours active-low)
    gpiod_line_settings_set_edge_detection(s, GPIOD_LINE_EDGE_RISING);
  if (spec.debounce_us > 0) gpiod_line_settings_set_debounce_period_us(s, spec.debounce_us);

  GpiodPtr<gpiod_line_config> line_config(checked(gpiod_line_config_new()));
  const unsigned offset = at.offset;
  if (gpiod_line_config_add_line_settings(line_config.get(), &offset, 1, s) < 0)
    throw std::runtime_error(describe(spec, role, at) + ": bad line settings: " + std::strerror(errno));
  GpiodPtr<gpiod_request_config> request_config(checked(gpiod_request_config_new()));
  gpiod_request_config_set_consumer(request_config.get(), consumer.c_str());

  gpiod_line_request* request = gpiod_chip_request_lines(chip.get(), request_config.get(), line_config.get());
  if (request == nullptr) {
    const int err = errno;
    std::string why = std::strerror(err);
    if (err == EBUSY) why += holder(chip.get(), offset);
    if (err == EINVAL && !is_output(role) && spec.bias != Bias::AsIs)
      why += " (does the chip support bias " + std::string(bias_name(spec.bias)) + "? try \"bias\": \"as-is\")";
    throw std::runtime_error("cannot request " + describe(spec, role, at) + ": " + why);
  }
  return request;
}

}  // namespace

void GpiodLines::RequestDeleter::operator()(gpiod_line_request* r) const { gpiod_line_request_release(r); }
void GpiodLines::BufferDeleter::operator()(gpiod_edge_event_buffer* b) const { gpiod_edge_event_buffer_free(b); }

GpiodLines::GpiodLines(const GpiodLinesConfig& config) {
  for (LineRole role : kLineRoles) {
    const LineSpec& spec = config.line(role);
    Line& line = lines_[index(role)];
    line.where = locate_line(config.chip, spec.name, role_key(role), config.device_dir);
    line.request.reset(request_line(line.where, spec, role, config.consumer));
    line.written = 0;
  }
  events_.reset(checked(gpiod_edge_event_buffer_new(kEventCapacity)));
  // Non-blocking event fd: read() then costs one read() syscall, EAGAIN when idle.
  const int fd = gpiod_line_request_get_fd(lines_[index(LineRole::CaptureButton)].request.get());
  const int flags = fcntl(fd, F_GETFL);
  if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0)
    throw std::runtime_error(std::string("cannot make the capture_button event queue non-blocking: ") +
                             std::strerror(errno));
}

GpiodLines::~GpiodLines() {
  for (LineRole role : {LineRole::AmpEnable, LineRole::StatusLed}) {
    Line& line = lines_[index(role)];
    if (!line.request) continue;
    line.written = -1;  // force the write
    (void)set(line, false);  // best effort: a failure is already counted
  }
}

capture::IoStatus GpiodLines::read(DigitalInputs& in) {
  bool ok = true;
  const Line& estop = lines_[index(LineRole::Estop)];
  const gpiod_line_value e = gpiod_line_request_get_value(estop.request.get(), estop.where.offset);
  if (e == GPIOD_LINE_VALUE_ERROR) {
    io_errors_.fetch_add(1, std::memory_order_relaxed);
    ok = false;
  }
  in.estop = e != GPIOD_LINE_VALUE_INACTIVE;  // an unreadable e-stop counts as asserted

  const Line& button = lines_[index(LineRole::CaptureButton)];
  const gpiod_line_value b = gpiod_line_request_get_value(button.request.get(), button.where.offset);
  if (b == GPIOD_LINE_VALUE_ERROR) {
    io_errors_.fetch_add(1, std::memory_order_relaxed);
    ok = false;
  }
  in.capture_button = b == GPIOD_LINE_VALUE_ACTIVE;

  const int n = gpiod_line_request_read_edge_events(button.request.get(), events_.get(), kEventCapacity);
  if (n < 0 && errno != EAGAIN) {
    io_errors_.fetch_add(1, std::memory_order_relaxed);
    ok = false;
  }
  for (int i = 0; i < n; ++i) {
    gpiod_edge_event* ev = gpiod_edge_event_buffer_get_event(events_.get(), static_cast<unsigned long>(i));
    // The kernel numbers this line's events 1, 2, 3…; only rising (= press) ones are requested.
    const std::uint64_t seqno = gpiod_edge_event_get_line_seqno(ev);
    if (seqno > presses_) presses_ = seqno;
  }
  in.capture_presses = presses_;
  return ok ? capture::IoStatus::ok : capture::IoStatus::error;
}

capture::IoStatus GpiodLines::write(const DigitalOutputs& out) {
  const bool enable_ok = set(lines_[index(LineRole::AmpEnable)], out.amp_enable);
  const bool led_ok = set(lines_[index(LineRole::StatusLed)], out.status_led);
  return enable_ok && led_ok ? capture::IoStatus::ok : capture::IoStatus::error;
}

// Only on change: the request is exclusive, so nothing else moves the line.
bool GpiodLines::set(Line& line, bool active) {
  const int want = active ? 1 : 0;
  if (line.written == want) return true;
  const int rc = gpiod_line_request_set_value(line.request.get(), line.where.offset,
                                              active ? GPIOD_LINE_VALUE_ACTIVE : GPIOD_LINE_VALUE_INACTIVE);
  if (rc < 0) {
    io_errors_.fetch_add(1, std::memory_order_relaxed);
    line.written = -1;  // retry next cycle
    return false;
  }
  line.written = want;
  return true;
}

}  // namespace knoblab::hal
