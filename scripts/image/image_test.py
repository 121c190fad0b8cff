#!/usr/bin/env python3
"""Boots the QEMU image headless and checks the appliance over its serial console.

QEMU's serial port is a unix socket this driver connects to; the console has
root's shell (autologin), so each check is a shell command whose output is
cut out between two markers. The store disk is a copy the test owns (the
image's stays empty), since a power cut must leave it for the second boot.
Checks, in order:

  ready         "appliance ready" appears on the console (boot-to-ready time)
  get_state     `knoblab ctl get_state` answers with the loop running, no fault
  kiosk         knoblab-ui runs on the emulated display: its status file shows
                the home screen with the loop running, and QEMU's screendump
                of the display (kept as kiosk.png) is that screen, its status
                strip drawn; killed, systemd puts it back up
  loop_thread   hapticd's loop thread (knoblab-rt) is SCHED_FIFO, pinned to CPU 1
  daq_modules   with daq.cfg's modules in the image: Comedi, IIO and counter load
  cyclictest    30 s on the isolated CPU; its figures are reported, never judged
  amp_enabled   render mode raises AMP_EN (read back from the gpio-sim line)
  capture_button  LED_STATUS is lit while idle; FOOTSW pressed and released
                on the gpio-sim chip reaches a subscribed client as hapticd's
                capture_button event, counted in get_state, starting nothing
  capture       a swept-sine capture of the simulated knob through hapticd is
                stored complete, every sample in the device's sqlite
  fit           `knoblab fit` on the device stores a fit that finds the knob's
                12 detents per revolution
  discrepancy   `knoblab discrepancy` on the device stores its result
  estop         ESTOP_N pulled low mid-capture latches hapticd's estop fault,
                drops AMP_EN and LED_STATUS, and the stored capture says
                "fault: estop"
  estop_clear   released and cleared, the fault list is empty again
  overrun       hapticd restarted at 20 kHz with the supervisor's own overrun
                limit (the image's drop-in lifts it under emulation), asked
                to render: its cycles outlast their 50 µs period, the overruns
                fault latches, AMP_EN and LED_STATUS drop and the loop runs
                on; then hapticd as the image runs it again
  amp_comms     the Modbus simulator killed mid-capture latches amp_comms and
                the stored capture says so; cleared once it is back
  power_cut     QEMU killed mid-trial of a study session (a simulated
                participant through hapticd's guided hand); after the next
                boot the store passes integrity_check, holds every sample of
                the trial's recording committed before the cut, and marks it
                incomplete
  study_resume  the same session run again resumes at the trial after the
                last one committed, every committed trial as it was
  clean_stop    hapticd stops on SIGTERM with exit status 0
  poweroff      the guest powers off and QEMU exits by itself

Writes report.json (the acceptance figures at its top level, then each
check's result and detail) and the consoles' logs to the image directory,
prints one line per check and "N passed, N failed".
"""
import argparse
import json
import struct
import zlib
import os
import re
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time

SOCK = "/run/knoblab/hapticd.sock"
CTL = f"knoblab ctl --socket {SOCK}"
DB = "/var/lib/knoblab/lab.sqlite"
LINE = "/usr/libexec/knoblab/sim-line"

# The simulated knob hapticd's sim backend turns (hapticd.json) and its truth.
KNOB = "moderate-detents"
KNOB_DETENTS_PER_REV = 12
# The Table 3 spatial sweep with the thesis' PID gains (the defaults), at
# the image's 2 kHz loop.
STIMULUS = "swept_sine.a=0 swept_sine.b=1.5 swept_sine.c=1 swept_sine.d=3"
CAPTURE_SECONDS = 5
CYCLICTEST_SECONDS = 30
# The study session the power cut interrupts: Study 2's list selection (no
# fine homing on the detented knob), installed with the kiosk.
STUDY = "/usr/share/knoblab/studies/list-selection.json"
SIMULATE = f"knoblab study simulate {STUDY} --participants 1 --db {DB}"
TRIALS = "SELECT trial_index, result_json, ratings_json, capture_id FROM study_trials ORDER BY trial_index"
STUDY_LOG = "/var/lib/knoblab/study-before-cut.log"
# How long each of the guest's polls before the cut may wait (for a committed
# trial, then for one under way); on a busy emulated host a trial with its
# commits takes a minute or more.
POWER_CUT_WAIT_S = 600
SESSION_RUNS = 4
# The overrun check's hapticd: at 20 kHz every emulated cycle outlasts its
# period; the supervisor's default limit (10 consecutive overruns) applies.
OVERRUN_DROPIN = "/run/systemd/system/hapticd.service.d/zz-overrun-check.conf"
OVERRUN_OPTS = "--rate 20000"

# Shell functions defined once in the guest's shell: an event caught by a
# watcher that subscribes before whatever causes it (`watch_event NAME`, then
# act, then `event_caught SECONDS`: the event's line, or nothing once SECONDS
# have passed, so a missing event cannot hang the console); and a capture
# whose capture_finished event is caught that way, in two halves so that a
# check can act in between.
GUEST_FUNCTIONS = r"""
watch_event() { rm -f /tmp/ev /tmp/ev.err; %(ctl)s --watch --events "$1" --count 1 >/tmp/ev 2>/tmp/ev.err & WATCHER=$!; until grep -q watching /tmp/ev.err 2>/dev/null; do kill -0 $WATCHER 2>/dev/null || return 1; sleep 0.1; done; }
event_caught() { n=$(( $1 * 10 )); while [ $n -gt 0 ] && kill -0 $WATCHER 2>/dev/null; do sleep 0.1; n=$(( n - 1 )); done; { kill $WATCHER; wait $WATCHER; } 2>/dev/null; cat /tmp/ev; }
start_capture() { watch_event capture_finished && %(ctl)s start_capture knob=%(knob)s %(stimulus)s "$@"; }
capture_finished() { event_caught "$1"; }
""" % {"ctl": CTL, "knob": KNOB, "stimulus": STIMULUS}


class Console:
    """The guest's serial console: everything read is kept (and logged)."""

    def __init__(self, path, log_path):
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.connect(path)
        self.text = ""
        self.cond = threading.Condition()
        self.log = open(log_path, "w", encoding="utf-8", errors="replace")
        self.closed = False
        threading.Thread(target=self._reader, daemon=True).start()
        self.seq = 0

    def _reader(self):
        while True:
            try:
                data = self.sock.recv(4096)
            except OSError:
                data = b""
            text = data.decode("utf-8", errors="replace")
            with self.cond:
                if not data:
                    self.closed = True
                else:
                    self.text += text
                    self.log.write(text)
                    self.log.flush()
                self.cond.notify_all()
            if not data:
                return

    def wait_for(self, pattern, timeout, start=0):
        """The first match of pattern in the console output after start."""
        deadline = time.monotonic() + timeout
        rx = re.compile(pattern)
        with self.cond:
            while True:
                m = rx.search(self.text, start)
                if m:
                    return m
                left = deadline - time.monotonic()
                if left <= 0 or self.closed:
                    raise TimeoutError(f"no {pattern!r} on the console after {timeout} s")
                self.cond.wait(left)

    def send(self, line):
        self.sock.sendall(line.encode() + b"\n")

    def run(self, command, timeout=60):
        """Runs a shell command in the guest: (exit status, output)."""
        self.seq += 1
        n = self.seq
        with self.cond:
            start = len(self.text)
        # The markers are split in the command so that the echo of the typed
        # line cannot match them; only the output does.
        self.send(f"echo '<<''<{n}'; {command}; echo \">>\"'>{n} '$?")
        m = self.wait_for(rf"(?s)<<<{n}\r?\n(.*?)>>>{n} (\d+)", timeout, start)
        out = m.group(1).replace("\r", "")
        return int(m.group(2)), out


def parse_json(text):
    """The first JSON object in text; what follows it is not its business (a
    second command's output, or a service's line on the console)."""
    i = text.find("{")
    return json.JSONDecoder().raw_decode(text[i:])[0] if i >= 0 else None


def sql(con, query):
    """Rows of a query on the device's store, read-only, as dicts (the
    query must not hold double quotes: it goes in a shell's)."""
    rc, out = con.run(f'sqlite3 -readonly -json {DB} "{query}"')
    if rc != 0:
        raise RuntimeError(f"sqlite3 exit {rc}: {out.strip()}")
    return json.loads(out) if out.strip() else []


class Boot:
    """One run of QEMU: its process and its console."""

    def __init__(self, args, tmp, store, log_name):
        self.con_path = os.path.join(tmp, f"{log_name}.sock")
        self.qmp_path = os.path.join(tmp, f"{log_name}.qmp")
        env = dict(os.environ, KNOBLAB_QEMU_CONSOLE=f"unix:{self.con_path}",
                   KNOBLAB_QEMU_STORE=store, KNOBLAB_QEMU_QMP=f"unix:{self.qmp_path}")
        self.t0 = time.monotonic()
        self.qemu = subprocess.Popen([args.qemu], env=env, stdin=subprocess.DEVNULL)
        while not os.path.exists(self.con_path):
            if self.qemu.poll() is not None:
                raise RuntimeError(f"qemu exited with {self.qemu.returncode} before opening its console")
            time.sleep(0.05)
        self.con = Console(self.con_path, os.path.join(args.image_dir, f"{log_name}.log"))

    def wait_ready(self, timeout):
        """Seconds from QEMU's start to "appliance ready"; then a quiet shell."""
        self.con.wait_for(r"appliance ready", timeout)
        seconds = round(time.monotonic() - self.t0, 1)
        # root's autologin shell: wait for its prompt, then quiet the console
        # (emulated on a busy host, the login alone has taken over 2 minutes).
        self.con.wait_for(r"root@knoblab:~# ", 600)
        self.con.send("stty -echo; PS1=''")
        # No job control: its "Done" notices would land in commands' output.
        self.con.run("set +m; dmesg -n 1")
        for definition in GUEST_FUNCTIONS.strip().splitlines():
            self.con.run(definition)
        return seconds

    def screendump(self, ppm_path):
        """The emulated display as a PPM file, through QEMU's QMP socket."""
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as q:
            q.connect(self.qmp_path)
            reader = q.makefile("r")

            def reply():
                while True:  # events may come before the reply
                    msg = json.loads(reader.readline())
                    if "return" in msg or "error" in msg:
                        return msg

            json.loads(reader.readline())  # the greeting
            for command in ({"execute": "qmp_capabilities"},
                            {"execute": "screendump", "arguments": {"filename": ppm_path}}):
                q.sendall(json.dumps(command).encode() + b"\n")
                msg = reply()
                if "error" in msg:
                    raise RuntimeError(f"QMP {command['execute']}: {msg['error']}")

    def kill(self):
        if self.qemu.poll() is None:
            self.qemu.kill()
            self.qemu.wait()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--image-dir", required=True)
    ap.add_argument("--qemu", required=True, help="scripts/image/qemu.sh")
    ap.add_argument("--ready-timeout", type=float, default=600)
    args = ap.parse_args()

    report = {"boot_to_ready_s": None, "kiosk_ok": False, "capture_ok": False, "fit_ok": False,
              "discrepancy_ok": False, "estop_ok": False, "amp_comms_ok": False,
              "power_cut_ok": False, "study_resume_ok": False, "sched_fifo_ok": False, "cyclictest": None,
              "checks": [], "figures": {}}

    def check(name, ok, detail, field=None):
        ok = bool(ok)
        report["checks"].append({"name": name, "ok": ok, "detail": detail})
        if field:
            report[field] = ok
        print(f"image-test: {'PASS' if ok else 'FAIL'} {name}: {detail}", flush=True)
        return ok

    tmp = tempfile.mkdtemp(prefix="knoblab-image-test-")
    store = os.path.join(tmp, "store.img")
    subprocess.run(["cp", "--sparse=always", os.path.join(args.image_dir, "store.img"), store], check=True)
    boot = None
    try:
        boot = Boot(args, tmp, store, "console")
        cut = first_boot(boot, args, report, check)
        boot.kill()  # the power cut: no shutdown, no flush from the guest
        boot = Boot(args, tmp, store, "console-after-power-cut")
        second_boot(boot, args, report, check, cut)
    except Exception as e:  # a check that could not even run fails the test
        check("driver", False, f"{type(e).__name__}: {e}")
    finally:
        if boot:
            boot.kill()
            report["figures"]["qemu_exit_status"] = boot.qemu.returncode
        shutil.rmtree(tmp, ignore_errors=True)
    report["build"] = build_figures(args.image_dir)

    with open(os.path.join(args.image_dir, "report.json"), "w") as f:
        json.dump(report, f, indent=2)
        f.write("\n")
    checks = report["checks"]
    passed = sum(c["ok"] for c in checks)
    failed = len(checks) - passed
    print(f"image-test: report in {os.path.join(args.image_dir, 'report.json')}")
    print(f"{passed} passed, {failed} failed")
    return 0 if failed == 0 and passed > 0 else 1


def build_figures(image_dir):
    """What ./run image recorded: each step's seconds, and the kernel's
    build-info (version, fragments, build and CPU seconds) when it has one."""
    out = {}
    try:
        with open(os.path.join(image_dir, "build-times.json")) as f:
            out["image"] = json.load(f)
        with open(out["image"].get("kernel_build_info", "")) as f:
            out["kernel"] = dict(line.rstrip("\n").split("=", 1) for line in f if "=" in line)
    except (OSError, ValueError):
        pass
    return out


def first_boot(boot, args, report, check):
    """Everything up to the power cut; returns what the cut left committed."""
    con, figures = boot.con, report["figures"]
    report["boot_to_ready_s"] = boot.wait_ready(args.ready_timeout)
    check("ready", True, f"'appliance ready' {report['boot_to_ready_s']} s after QEMU started")
    rc, out = con.run("uname -r")
    figures["kernel"] = out.strip()
    # Where the boot's time went: "Startup finished in Xs (kernel) + Ys (userspace)".
    rc, out = con.run("systemd-analyze time | head -1")
    figures["systemd_analyze"] = out.strip()

    rc, out = con.run(f"{CTL} get_state")
    state = parse_json(out) if rc == 0 else None
    report["get_state"] = state
    check("get_state", state and state.get("cycles", 0) > 0 and state.get("faults") == [],
          f"exit {rc}, cycles {state and state.get('cycles')}, faults {state and state.get('faults')}, "
          f"modbus {state and state.get('modbus')}")

    # One check's error (a timeout, a query that fails) fails that check;
    # the next still runs.
    def guarded(name, fn, *fn_args):
        try:
            return fn(*fn_args)
        except Exception as e:
            check(name, False, f"{type(e).__name__}: {e}")

    guarded("kiosk", check_kiosk, boot, args, report, check)
    guarded("loop_thread", check_loop_thread, con, report, check)
    guarded("daq_modules", check_daq_modules, con, report, check)
    guarded("cyclictest", run_cyclictest, con, report, check)
    guarded("amp_enabled", check_amp_enabled, con, check)
    guarded("capture_button", check_capture_button, con, report, check)
    capture_id = guarded("capture", check_capture, con, report, check)
    if capture_id is not None:
        guarded("fit", check_fit, con, report, check, capture_id)
        guarded("discrepancy", check_discrepancy, con, report, check, capture_id)
    guarded("estop", check_estop, con, report, check)
    guarded("amp_comms", check_amp_comms, con, report, check)
    guarded("overrun", check_overrun, con, report, check)
    return start_power_cut(con, report)


def second_boot(boot, args, report, check, cut):
    con, figures = boot.con, report["figures"]
    figures["boot_to_ready_after_power_cut_s"] = boot.wait_ready(args.ready_timeout)
    check_power_cut(con, report, check, cut)
    check_study_resume(con, report, check, cut)

    rc, out = con.run("systemctl stop hapticd; systemctl show -P ExecMainStatus hapticd", timeout=60)
    check("clean_stop", rc == 0 and out.strip() == "0", f"hapticd's exit status {out.strip()!r}")

    t = time.monotonic()
    con.send("systemctl poweroff")
    try:
        boot.qemu.wait(timeout=180)
        figures["poweroff_s"] = round(time.monotonic() - t, 1)
        check("poweroff", boot.qemu.returncode == 0,
              f"QEMU exited with {boot.qemu.returncode} {figures['poweroff_s']} s after poweroff")
    except subprocess.TimeoutExpired:
        check("poweroff", False, "QEMU still running 180 s after poweroff")


def read_ppm(path):
    """(width, height, RGB bytes) of a binary PPM (P6, 8 bits)."""
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:  # magic, width, height, maxval; comments skipped
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    if fields[0] != b"P6" or int(fields[3]) != 255:
        raise ValueError(f"{path}: not an 8-bit P6 PPM")
    w, h = int(fields[1]), int(fields[2])
    return w, h, data[pos + 1:pos + 1 + 3 * w * h]


def write_png(path, w, h, rgb):
    """RGB bytes as a PNG file (zlib only: no imaging library on the host)."""
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    rows = b"".join(b"\x00" + rgb[3 * w * y:3 * w * (y + 1)] for y in range(h))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows, 6)) + chunk(b"IEND", b""))


# The status strip's background, Theme.surface in apps/ui/qml/Theme.qml.
STRIP_RGB = (0x20, 0x25, 0x2b)


def check_kiosk(boot, args, report, check):
    """The kiosk's home screen with the loop running: what it says it shows
    (its status file), and the display's pixels (a screendump) agreeing."""
    con = boot.con
    status, deadline = {}, time.monotonic() + 180
    while time.monotonic() < deadline:
        rc, out = con.run("cat /run/knoblab-ui/status.json 2>/dev/null")
        status = (parse_json(out) or {}).get("texts", {}) if rc == 0 else {}
        if re.match(r"loop \d", status.get("loop", "")) and status.get("connection") == "● hapticd":
            break
        time.sleep(2)
    report["kiosk_status"] = status
    # The texts change before the next frame reaches the framebuffer (software
    # rendering under emulation lags): screendumps until the pixels agree, i.e.
    # the strip's left part, where a lost link shows in red, has no red.
    ppm = os.path.join(args.image_dir, "kiosk.ppm")
    png = os.path.join(args.image_dir, "kiosk.png")
    deadline = time.monotonic() + 60
    while True:
        boot.screendump(ppm)
        w, h, rgb = read_ppm(ppm)
        pixels = [rgb[i:i + 3] for i in range(0, len(rgb), 3)]
        left = [pixels[y * w + x] for y in range(0, 40) for x in range(0, int(0.45 * w))]
        red = sum(p[0] > 200 and p[1] < 140 and p[2] < 140 for p in left) / len(left)
        if red == 0 or time.monotonic() > deadline:
            break
        time.sleep(2)
    write_png(png, w, h, rgb)
    os.remove(ppm)
    most = max(set(pixels[::97]), key=pixels[::97].count)
    drawn = sum(p != most for p in pixels[::7]) / len(pixels[::7])
    # The strip: the top 30 rows, their background the theme's surface.
    top = pixels[:30 * w]
    strip = sum(tuple(p) == STRIP_RGB for p in top) / len(top)
    loop = status.get("loop", "")
    check("kiosk", re.match(r"loop \d", loop) and status.get("daemonStatus", "").startswith("hapticd is")
          and drawn > 0.02 and strip > 0.5 and red == 0,
          f"{w}x{h} screendump in {png}: {100 * drawn:.0f} % drawn, status strip {100 * strip:.0f} % of the top rows, "
          f"{100 * red:.2f} % red in its left part (a lost link); "
          f"the kiosk says {loop!r}, {status.get('connection')!r}, {status.get('daemonStatus')!r}", "kiosk_ok")
    # A crash: systemd puts the screen up again.
    rc, before = con.run("systemctl show -P MainPID knoblab-ui")
    con.run("systemctl kill -s SIGSEGV knoblab-ui")
    after, deadline = before, time.monotonic() + 120
    while time.monotonic() < deadline:
        time.sleep(3)
        rc, after = con.run("systemctl is-active knoblab-ui; systemctl show -P MainPID knoblab-ui")
        if after.split()[:1] == ["active"] and after.split()[1:] != before.split():
            break
    check("kiosk_restart", after.split()[:1] == ["active"] and after.split()[1:] != before.split(),
          f"MainPID {before.strip()} killed; now {' '.join(after.split())}")


def check_loop_thread(con, report, check):
    """The loop thread by name: its policy and priority from /proc's stat,
    the CPUs it may run on from status."""
    script = ("p=$(pidof hapticd); for t in /proc/$p/task/*; do "
              "echo \"$(cat $t/stat) | $(grep Cpus_allowed_list $t/status)\"; done")
    rc, out = con.run(script)
    threads = []
    for line in out.splitlines():
        m = re.match(r"(\d+) \((.*)\) (.*) \| Cpus_allowed_list:\s*(\S+)", line)
        if not m:
            continue
        rest = m.group(3).split()  # fields from the 3rd (state) on
        threads.append({"tid": int(m.group(1)), "name": m.group(2),
                        "policy": {0: "SCHED_OTHER", 1: "SCHED_FIFO", 2: "SCHED_RR"}.get(int(rest[38]), rest[38]),
                        "rt_priority": int(rest[37]), "last_cpu": int(rest[36]),
                        "cpus_allowed": m.group(4)})
    report["hapticd_threads"] = threads
    loop = [t for t in threads if t["name"] == "knoblab-rt"]
    ok = len(loop) == 1 and loop[0]["policy"] == "SCHED_FIFO" and loop[0]["cpus_allowed"] == "1"
    detail = (f"{loop[0]['policy']} priority {loop[0]['rt_priority']}, CPUs {loop[0]['cpus_allowed']}"
              if loop else f"no knoblab-rt thread among {[t['name'] for t in threads]}")
    check("loop_thread", ok, detail, "sched_fifo_ok")


def check_daq_modules(con, report, check):
    """A kernel built with daq.cfg has Comedi, IIO and counter as modules:
    they must load (a kernel without modules skips this check)."""
    rc, out = con.run("test -d /usr/lib/modules/$(uname -r) && echo yes || echo no")
    if out.strip() != "yes":
        return
    rc, out = con.run("modprobe -a comedi industrialio counter && cut -d' ' -f1 /proc/modules | sort | tr '\\n' ' '")
    report["modules_loaded"] = out.split()
    check("daq_modules", rc == 0 and {"comedi", "industrialio", "counter"} <= set(out.split()),
          f"modprobe exit {rc}, loaded: {out.strip()}")


def run_cyclictest(con, report, check):
    """cyclictest on the loop's isolated CPU, above the loop's priority, with
    hapticd running: what a thread there waits past its timer. Under
    software emulation these are no realtime figures; they are reported for
    comparison between runs, and only a run without figures fails."""
    rc, out = con.run(f"cyclictest --mlockall --priority=90 --affinity=1 --interval=1000 "
                      f"--duration={CYCLICTEST_SECONDS} --quiet", timeout=CYCLICTEST_SECONDS + 120)
    m = re.search(r"C:\s*(\d+)\s+Min:\s*(\d+)\s+Act:\s*\d+\s+Avg:\s*(\d+)\s+Max:\s*(\d+)", out)
    if m:
        report["cyclictest"] = {"min": int(m.group(2)), "avg": int(m.group(3)), "max": int(m.group(4)),
                                "unit": "us", "cycles": int(m.group(1)), "interval_us": 1000,
                                "seconds": CYCLICTEST_SECONDS, "cpu": 1, "priority": 90}
    c = report["cyclictest"]
    check("cyclictest", rc == 0 and m,
          f"{c['cycles']} cycles on CPU 1: min {c['min']} µs, avg {c['avg']} µs, max {c['max']} µs "
          f"(emulated: reported, not judged)" if c else f"exit {rc}: {out.strip()[-200:]}")


def check_amp_enabled(con, check):
    con.run(f"{CTL} load_model M_acc=1.3e-5 B_vel=2e-4 A_pos=0.01 P_pos=0.05")
    rc, out = con.run(f"{CTL} set_mode mode=render >/dev/null && sleep 1 && {LINE} AMP_EN")
    amp = out.strip().splitlines()[-1:]
    check("amp_enabled", rc == 0 and amp == ["1"], f"set_mode render exit {rc}, AMP_EN {amp}")
    con.run(f"{CTL} set_mode mode=idle >/dev/null")


def restart_hapticd(con, timeout=300):
    """systemctl restart hapticd, then get_state once it answers with its
    loop running ({} if it never did). knoblab-ready restarts with it (it
    requires hapticd) and prints "appliance ready" on this console: restarted
    here by name, systemctl returns once it has, so that line cannot fall into
    a later command's output."""
    con.run("systemctl daemon-reload && systemctl restart hapticd knoblab-ready", timeout=600)
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        rc, out = con.run(f"{CTL} get_state 2>/dev/null")
        state = parse_json(out) if rc == 0 else None
        if state and state.get("cycles", 0) > 0:
            return state
        time.sleep(1)
    return {}


def check_overrun(con, report, check):
    """The supervisor's overrun path end to end, although the image's loop
    runs slowed under emulation: hapticd at 20 kHz with its default overrun
    limit, asked to render; its cycles cannot keep their period, so the
    overruns fault latches, the motor goes safe (AMP_EN and the status LED
    low, render refused) and the loop runs on, counting them."""
    con.run(f"mkdir -p {os.path.dirname(OVERRUN_DROPIN)} && "
            f"printf '[Service]\\nEnvironment=\"HAPTICD_OPTS={OVERRUN_OPTS}\"\\n' > {OVERRUN_DROPIN}")
    try:
        started = restart_hapticd(con)
        con.run(f"{CTL} set_mode mode=render >/dev/null 2>&1")
        state, deadline = {}, time.monotonic() + 60
        while time.monotonic() < deadline:
            rc, out = con.run(f"{CTL} get_state")
            state = (parse_json(out) if rc == 0 else None) or {}
            if "overruns" in state.get("faults", []):
                break
            time.sleep(1)
        time.sleep(1)  # the safe state is taken in the cycle that latched; give the line a moment
        rc, out = con.run(f"{LINE} AMP_EN; {LINE} LED_STATUS")
        lines = out.strip().splitlines()
        rc, out = con.run(f"{CTL} get_state")
        after = parse_json(out) or {}
        rc, out = con.run(f"{CTL} set_mode mode=render 2>&1")
        refused = rc != 0 and "fault is latched" in out
    finally:
        con.run(f"rm -f {OVERRUN_DROPIN}")
        again = restart_hapticd(con)
    report["overrun"] = {"options": OVERRUN_OPTS, "started": started, "latched": state, "after": after,
                         "lines": lines[:2], "render_refused": refused, "restored": again}
    ok = ("overruns" in state.get("faults", []) and lines[:2] == ["0", "0"] and refused and
          after.get("cycles", 0) > state.get("cycles", 0) and again.get("faults") == [] and
          again.get("rate_hz") == 2000)
    check("overrun", ok,
          f"at {state.get('rate_hz')} Hz faults {state.get('faults')}; then AMP_EN, LED_STATUS {lines[:2]}, "
          f"render refused {refused}, cycles {state.get('cycles')} → {after.get('cycles')}; "
          f"restored at {again.get('rate_hz')} Hz, faults {again.get('faults')}")


def caught_event(con, command, seconds):
    """The data of the event the guest's watcher caught ({} if none came)."""
    rc, out = con.run(f"{command} {int(seconds)}", timeout=seconds + 60)
    event = parse_json(out)
    return event.get("data", {}) if event else {}


def finished_event(con, timeout):
    """The capture_finished event the guest's watcher caught."""
    return caught_event(con, "capture_finished", timeout)


def check_capture_button(con, report, check):
    """The status LED lit while idle; then the footswitch (active low, held
    up by hapticd's pull-up request) pressed for 0.2 s and released: one
    capture_button event, counted in get_state, and nothing started."""
    rc, out = con.run(f"{LINE} LED_STATUS && {CTL} get_state")
    before = parse_json(out) or {}
    led_idle = out.strip().splitlines()[:1]
    rc, out = con.run(f"watch_event capture_button && {LINE} FOOTSW pull-down && sleep 0.2 && "
                      f"{LINE} FOOTSW pull-up")
    event = caught_event(con, "event_caught", 30)  # also ends the watcher if the press failed
    rc2, out = con.run(f"{CTL} get_state")
    after = parse_json(out) or {}
    report["capture_button"] = {"led_idle": led_idle, "state_before": before, "event": event,
                                "state_after": after}
    presses = before.get("capture_button_presses")
    check("capture_button", led_idle == ["1"] and before.get("mode") == "idle" and rc == 0 and
          presses is not None and event.get("new") == 1 and event.get("presses") == presses + 1 and
          after.get("capture_button_presses") == presses + 1 and after.get("recording") is False,
          f"LED_STATUS {led_idle} while {before.get('mode')}; press → event {event}; get_state then counts "
          f"{after.get('capture_button_presses')} presses, recording {after.get('recording')}")


def stored_capture(con, capture_id):
    rows = sql(con, "SELECT status, sample_count, end_reason, "
                    "(SELECT count(*) FROM samples WHERE capture_id = c.id) AS rows "
                    f"FROM captures c WHERE id = {int(capture_id)}")
    return rows[0] if rows else {}


def check_capture(con, report, check):
    """A capture through hapticd, stored complete: its event, its row and
    every one of its samples in the device's sqlite. Returns its id."""
    rc, out = con.run(f"start_capture seconds={CAPTURE_SECONDS}")
    expected = (parse_json(out) or {}).get("samples")
    # The loop runs behind under emulation: give it twenty times the length.
    event = finished_event(con, timeout=CAPTURE_SECONDS * 20 + 60)
    capture_id = event.get("capture_id")
    row = stored_capture(con, capture_id) if capture_id is not None else {}
    report["capture"] = {"expected_samples": expected, "event": event, "stored": row}
    check("capture", rc == 0 and event.get("complete") and expected and
          row.get("status") == "complete" and row.get("sample_count") == expected == row.get("rows"),
          f"capture {capture_id}: {expected} samples expected, event {event}, stored {row}", "capture_ok")
    return capture_id if event.get("complete") else None


def check_fit(con, report, check, capture_id):
    """The fit runs on the device and is stored beside the capture; it must
    find the simulated knob's detents, or it fitted nothing real."""
    t = time.monotonic()
    rc, out = con.run(f"knoblab fit --capture {capture_id} --db {DB}", timeout=600)
    seconds = round(time.monotonic() - t, 1)
    rows = sql(con, "SELECT id, model, json_extract(result, '$.detents.per_rev') AS per_rev, "
                    "json_extract(result, '$.fit_percent') AS fit_percent "
                    f"FROM fits WHERE capture_id = {int(capture_id)}")
    report["fit"] = {"exit": rc, "seconds": seconds, "stored": rows}
    per_rev = rows[-1]["per_rev"] if rows else None
    check("fit", rc == 0 and len(rows) == 1 and per_rev and abs(per_rev - KNOB_DETENTS_PER_REV) < 0.1,
          f"exit {rc} in {seconds} s; stored fits {rows} (the knob has {KNOB_DETENTS_PER_REV} detents "
          f"per revolution)", "fit_ok")


def check_discrepancy(con, report, check, capture_id):
    """Discrepancy runs on the device and stores its result beside the
    capture: the stored JSON names the base model's figures."""
    t = time.monotonic()
    rc, out = con.run(f"knoblab discrepancy --capture {capture_id} --db {DB}", timeout=900)
    seconds = round(time.monotonic() - t, 1)
    rows = sql(con, "SELECT id, json_extract(result, '$.base.fit_percent') AS base_fit_percent, "
                    "json_array_length(result, '$.findings') AS findings "
                    f"FROM discrepancies WHERE capture_id = {int(capture_id)}")
    report["discrepancy"] = {"exit": rc, "seconds": seconds, "stored": rows, "output": out.strip()[-2000:]}
    check("discrepancy", rc == 0 and len(rows) == 1 and rows[0]["base_fit_percent"] is not None,
          f"exit {rc} in {seconds} s; stored {rows}", "discrepancy_ok")


def check_estop(con, report, check):
    """Pulling ESTOP_N low mid-capture must latch the e-stop, drop AMP_EN and
    end the capture stored incomplete with the fault; releasing and clearing
    must empty the fault list."""
    rc, out = con.run(f"start_capture seconds=120 >/dev/null && sleep 2 && {LINE} AMP_EN")
    amp_before = out.strip().splitlines()[-1:]
    rc, out = con.run(f"{LINE} ESTOP_N pull-down && sleep 1 && {LINE} AMP_EN && {LINE} LED_STATUS && "
                      f"{CTL} get_state")
    lines = out.strip().splitlines()
    state = parse_json(out) or {}
    amp_after = lines[0] if lines else None
    led_after = lines[1] if len(lines) > 1 else None
    event = finished_event(con, timeout=60)
    row = stored_capture(con, event["capture_id"]) if "capture_id" in event else {}
    report["estop"] = {"state": state, "event": event, "stored": row, "led_status": led_after}
    check("estop", amp_before == ["1"] and "estop" in state.get("faults", []) and amp_after == "0"
          and led_after == "0"
          and event.get("end_reason") == "fault: estop" and row.get("status") == "incomplete"
          and row.get("end_reason") == "fault: estop",
          f"AMP_EN {amp_before} while capturing, then faults {state.get('faults')}, AMP_EN {amp_after}, "
          f"LED_STATUS {led_after}; capture {event.get('capture_id')} stored {row.get('status')} "
          f"({row.get('end_reason')})", "estop_ok")

    # clear_fault's reply may predate the loop's next cycle, which does the
    # clearing: the state a moment later says whether it took.
    rc, out = con.run(f"{LINE} ESTOP_N pull-up && sleep 0.5 && {CTL} clear_fault >/dev/null && "
                      f"sleep 0.5 && {CTL} get_state")
    state = parse_json(out) or {}
    check("estop_clear", rc == 0 and state.get("faults") == [],
          f"after release and clear_fault: faults {state.get('faults')}")


def check_amp_comms(con, report, check):
    """The amplifier's Modbus link lost mid-capture (its simulator killed):
    hapticd latches amp_comms and the stored capture says so; once systemd
    has the simulator back, clear_fault empties the fault list."""
    rc, out = con.run("start_capture seconds=120 >/dev/null && sleep 2 && "
                      "systemctl kill --signal=SIGKILL knoblab-modbus-sim && sleep 2 && "
                      f"{CTL} get_state")
    state = parse_json(out) or {}
    event = finished_event(con, timeout=60)
    row = stored_capture(con, event["capture_id"]) if "capture_id" in event else {}
    # Back when the simulator's unit is active again (it restarts on failure).
    con.run("until systemctl is-active -q knoblab-modbus-sim; do sleep 0.5; done; sleep 1", timeout=120)
    rc2, out = con.run(f"{CTL} clear_fault >/dev/null && sleep 1 && {CTL} get_state")
    after = parse_json(out) or {}
    report["amp_comms"] = {"state": state, "event": event, "stored": row, "after_clear": after}
    check("amp_comms", "amp_comms" in state.get("faults", []) and
          event.get("end_reason") == "fault: amp_comms" and row.get("end_reason") == "fault: amp_comms"
          and after.get("faults") == [],
          f"faults {state.get('faults')} after the kill; capture {event.get('capture_id')} stored "
          f"{row.get('status')} ({row.get('end_reason')}); after the restart and clear_fault: "
          f"faults {after.get('faults')}", "amp_comms_ok")


def start_power_cut(con, report):
    """A study session in the background, and what it has committed once a
    trial is in and the next one's recording has its first seconds in the
    store: the caller then kills QEMU at once, mid-trial."""
    # Listed before the session: emulated and busy, a listing takes long
    # enough for a trial to end, so none is taken between the poll and the cut.
    rc, listing = con.run(f"knoblab list --db {DB}", timeout=300)
    report["power_cut"] = {"list_before_session": listing.splitlines()}
    # In a subshell: the driver appends "; echo …" to the line, and "&;" is no shell.
    con.run(f"( nohup {SIMULATE} >{STUDY_LOG} 2>&1 & )")
    # The trials committed once there is one: the check after the reboot
    # wants them unchanged (a prefix of what the store then holds).
    said, waited = poll_session(con, '[ "${1:-0}" -ge 1 ]', "trials")
    trials = sql(con, TRIALS) if said[:1] == ["trials"] else []
    # Then a trial's recording within its first 2 s: it has at least its
    # remaining baseline and the task to run, and the guest says so as its
    # last word, so QEMU is killed before that trial can end.
    if trials:
        said, more = poll_session(con, '[ -n "$4" ] && [ "$4" -gt 0 ] && [ "$4" -lt $((2 * $3)) ]', "cut",
                                  runs=int(said[1]))
        waited += more
    # The poll's words: what it saw, the session's runs, then trials,
    # recording capture, rate and rows.
    cut = {}
    if said[:1] == ["cut"]:
        cut = {"id": int(said[3]), "rows": int(said[5]), "trials": trials}
    runs = int(said[1]) if len(said) > 1 else None
    report["power_cut"].update({"waited_s": waited, "poll_said": " ".join(said), "session_runs": runs,
                                "committed_before_cut": {k: v for k, v in cut.items() if k != "trials"},
                                "trials_before_cut": len(trials)})
    # The session's own words when it ended early (each run's, appended).
    rc, log = con.run(f"grep -i error {STUDY_LOG} | tail -n 5")
    report["power_cut"]["study_log"] = log.strip().splitlines()
    return cut


def poll_session(con, condition, seen, runs=1):
    """The guest polls its own store until `condition` holds for the words of
    the poll (trials, recording capture, its rate, its rows), then says
    "SEEN RUNS WORDS…" as its last word; no round trip over the console falls
    between the two (a busy emulated host is slow at both). A session that
    ends first is run again, as an experimenter would (it resumes), up to
    SESSION_RUNS runs in all, counting the `runs` before this poll; it then
    says "ended …", and "timeout …" after POWER_CUT_WAIT_S. Returns the words
    said and the seconds waited."""
    poll = ("SELECT (SELECT count(*) FROM study_trials) || ' ' || coalesce((SELECT id || ' ' || "
            "CAST(rate_hz AS INTEGER) || ' ' || (SELECT count(*) FROM samples WHERE capture_id = c.id) "
            "FROM captures c WHERE status = 'recording'), '')")
    started = time.monotonic()
    rc, out = con.run(
        f"end=$(( $(date +%s) + {POWER_CUT_WAIT_S} )); runs={int(runs)}; while :; do "
        f"set -- $(sqlite3 -readonly {DB} \"{poll}\"); "
        f"if {condition}; then echo \"{seen} $runs $*\"; break; fi; "
        f"if ! pgrep -f '[s]tudy simulate' >/dev/null; then "
        f"[ $runs -lt {SESSION_RUNS} ] || {{ echo \"ended $runs $*\"; break; }}; "
        f"runs=$((runs + 1)); ( nohup {SIMULATE} >>{STUDY_LOG} 2>&1 & ); sleep 1; fi; "
        f"[ $(date +%s) -lt $end ] || {{ echo \"timeout $runs $*\"; break; }}; sleep 0.2; done",
        timeout=POWER_CUT_WAIT_S + 120)
    return out.strip().split(), round(time.monotonic() - started, 1)


def check_study_resume(con, report, check, cut):
    """The session the cut interrupted, run again for one trial: it resumes
    after the last trial committed, and those before the cut are unchanged."""
    before = cut.get("trials", [])
    committed = sql(con, TRIALS)
    rc, out = con.run(f"{SIMULATE} --max-trials 1", timeout=300)
    after = sql(con, TRIALS)
    expected = f"resumed at trial {len(committed) + 1}"
    report["study_resume"] = {"trials_before_cut": len(before), "trials_after_reboot": len(committed),
                              "trials_after_resume": len(after), "output": out.strip().splitlines()[-3:]}
    check("study_resume", rc == 0 and before and expected in out and after[:len(before)] == before
          and len(after) == len(committed) + 1,
          f"{len(before)} trials committed before the cut, {len(committed)} after the reboot; "
          f"run again: exit {rc}, {expected!r} {'said' if expected in out else 'not said'}, "
          f"{len(after)} trials now, the first {len(before)} {'unchanged' if after[:len(before)] == before else 'CHANGED'}",
          "study_resume_ok")


def check_power_cut(con, report, check, cut):
    rc, out = con.run(f"sqlite3 -readonly {DB} 'PRAGMA integrity_check'", timeout=300)
    integrity = out.strip()
    row = stored_capture(con, cut["id"]) if "id" in cut else {}
    report["power_cut"].update({"integrity_check": integrity, "after_reboot": row})
    check("power_cut", integrity == "ok" and cut.get("rows", 0) > 0 and row.get("rows", -1) >= cut["rows"]
          and row.get("status") == "incomplete" and row.get("sample_count") == row.get("rows"),
          f"integrity_check {integrity!r}; capture {cut.get('id')}: {cut.get('rows')} samples committed "
          f"before the cut, {row.get('rows')} after the reboot, stored {row.get('status')} "
          f"({row.get('end_reason')})" + session_runs(report["power_cut"])
          + ("" if cut else why_no_cut(report["power_cut"])), "power_cut_ok")


def session_runs(power_cut):
    """For a check's line: a session that had to be run again before the cut."""
    runs = power_cut.get("session_runs") or 1
    return "" if runs == 1 else (f"; the session ran {runs} times before the cut, ending with "
                                 f"{power_cut.get('study_log', [])[-1:]}")


def why_no_cut(power_cut):
    """For a check's line: what the guest's poll last saw and the session's
    last words, when no trial was under way to cut."""
    return (f"; no trial under way to cut after {power_cut.get('waited_s')} s, the poll said "
            f"{power_cut.get('poll_said')!r} (session runs, trials, recording capture, rate, rows); "
            f"the session's errors end {power_cut.get('study_log', [])[-2:]}")


if __name__ == "__main__":
    sys.exit(main())
