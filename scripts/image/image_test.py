#!/usr/bin/env python3
"""Boots the QEMU image headless and checks the appliance over its serial console.

QEMU's serial port is a unix socket this driver connects to; the console has
root's shell (autologin), so each check is a shell command whose output is
cut out between two markers. Checks, in order:

  ready         "appliance ready" appears on the console (boot-to-ready time)
  get_state     `knoblab ctl get_state` answers with the loop running, no fault
  loop_thread   hapticd's loop thread (knoblab-rt) is SCHED_FIFO, pinned to CPU 1
  daq_modules   with daq.cfg's modules in the image: Comedi, IIO and counter load
  amp_enabled   render mode raises AMP_EN (read back from the gpio-sim line)
  estop         ESTOP_N pulled low latches hapticd's estop fault and drops AMP_EN
  estop_clear   released and cleared, the fault list is empty again
  clean_stop    hapticd stops on SIGTERM with exit status 0
  poweroff      the guest powers off and QEMU exits by itself

Writes report.json (figures and each check's result) and console.log to the
image directory, prints one line per check and "N passed, N failed".
"""
import argparse
import json
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
    i = text.find("{")
    return json.loads(text[i:]) if i >= 0 else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--image-dir", required=True)
    ap.add_argument("--qemu", required=True, help="scripts/image/qemu.sh")
    ap.add_argument("--ready-timeout", type=float, default=600)
    args = ap.parse_args()

    report = {"checks": [], "figures": {}}
    checks = report["checks"]

    def check(name, ok, detail):
        checks.append({"name": name, "ok": bool(ok), "detail": detail})
        print(f"image-test: {'PASS' if ok else 'FAIL'} {name}: {detail}", flush=True)
        return ok

    tmp = tempfile.mkdtemp(prefix="knoblab-image-test-")
    con_path = os.path.join(tmp, "console.sock")
    env = dict(os.environ, KNOBLAB_QEMU_CONSOLE=f"unix:{con_path}")
    # -snapshot: the test's writes to the store disk go to a temporary file.
    t0 = time.monotonic()
    qemu = subprocess.Popen([args.qemu, "-snapshot"], env=env, stdin=subprocess.DEVNULL)
    try:
        while not os.path.exists(con_path):
            if qemu.poll() is not None:
                raise RuntimeError(f"qemu exited with {qemu.returncode} before opening its console")
            time.sleep(0.05)
        con = Console(con_path, os.path.join(args.image_dir, "console.log"))
        run_checks(con, qemu, t0, args, report, check)
    except Exception as e:  # a check that could not even run fails the test
        check("driver", False, f"{type(e).__name__}: {e}")
    finally:
        if qemu.poll() is None:
            qemu.kill()
            qemu.wait()
        shutil.rmtree(tmp, ignore_errors=True)
    report["figures"]["qemu_exit_status"] = qemu.returncode
    report["build"] = build_figures(args.image_dir)

    with open(os.path.join(args.image_dir, "report.json"), "w") as f:
        json.dump(report, f, indent=2)
        f.write("\n")
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


def run_checks(con, qemu, t0, args, report, check):
    figures = report["figures"]
    con.wait_for(r"appliance ready", args.ready_timeout)
    figures["boot_to_ready_s"] = round(time.monotonic() - t0, 1)
    check("ready", True, f"'appliance ready' {figures['boot_to_ready_s']} s after QEMU started")

    # root's autologin shell: wait for its prompt, then quiet the console.
    con.wait_for(r"root@knoblab:~# ", 120)
    con.send("stty -echo; PS1=''")
    rc, out = con.run("dmesg -n 1; uname -r")
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

    check_loop_thread(con, report, check)
    check_daq_modules(con, report, check)
    check_estop(con, report, check)

    rc, out = con.run("systemctl stop hapticd; systemctl show -P ExecMainStatus hapticd", timeout=60)
    check("clean_stop", rc == 0 and out.strip() == "0", f"hapticd's exit status {out.strip()!r}")

    t = time.monotonic()
    con.send("systemctl poweroff")
    try:
        qemu.wait(timeout=180)
        figures["poweroff_s"] = round(time.monotonic() - t, 1)
        check("poweroff", qemu.returncode == 0,
              f"QEMU exited with {qemu.returncode} {figures['poweroff_s']} s after poweroff")
    except subprocess.TimeoutExpired:
        check("poweroff", False, "QEMU still running 180 s after poweroff")


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
    check("loop_thread", ok, detail)


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


def check_estop(con, report, check):
    """Render mode enables the amplifier; pulling ESTOP_N low must latch the
    e-stop and drop AMP_EN; releasing and clearing must empty the fault list."""
    line = "/usr/libexec/knoblab/sim-line"
    con.run(f"{CTL} load_model M_acc=1.3e-5 B_vel=2e-4 A_pos=0.01 P_pos=0.05")
    rc, out = con.run(f"{CTL} set_mode mode=render && sleep 1 && {line} AMP_EN")
    amp_on = out.strip().splitlines()[-1:] == ["1"]
    check("amp_enabled", rc == 0 and amp_on, f"set_mode render exit {rc}, AMP_EN {out.strip().splitlines()[-1:]}")

    rc, out = con.run(f"{line} ESTOP_N pull-down && sleep 1 && {line} AMP_EN && {CTL} get_state")
    lines = out.strip().splitlines()
    state = parse_json(out) or {}
    amp_after = lines[0] if lines else None
    report["estop_state"] = state
    check("estop", "estop" in state.get("faults", []) and amp_after == "0",
          f"faults {state.get('faults')}, mode {state.get('mode')}, AMP_EN {amp_after}")

    # clear_fault's reply may predate the loop's next cycle, which does the
    # clearing: the state a moment later says whether it took.
    rc, out = con.run(f"{line} ESTOP_N pull-up && sleep 0.5 && {CTL} clear_fault >/dev/null && "
                      f"sleep 0.5 && {CTL} get_state")
    state = parse_json(out) or {}
    check("estop_clear", rc == 0 and state.get("faults") == [],
          f"after release and clear_fault: faults {state.get('faults')}")


if __name__ == "__main__":
    sys.exit(main())
