#!/usr/bin/env python3
"""Runs the shell command blocks of README.md and docs/*.md as a newcomer would.

Every ```sh block is run, line by line, in a scratch directory; a command that exits
non-zero fails the test. A block may be preceded by a directive comment:

  <!-- doc-test: skip REASON -->       not run here, and why (e.g. it builds an image)
  <!-- doc-test: with DIR -->          DIR's entries (relative to the repository) are
                                       linked into the scratch directory first
  <!-- doc-test: hapticd -->           hapticd runs on the simulated camera meanwhile
                                       ($KNOBLAB_SOCKET names its socket)

How a line is read: `./run knoblab ARGS` is `knoblab ARGS` and `./run shell CMD` is CMD
(this test already runs inside the sysroot); a bare `./run shell` opens an interactive
shell and is left out. Lines of a `$ ` transcript are commands, the rest their output.
/tmp/ in a command means the block's scratch directory. hapticd started without --cycles
and knoblab-modbus-sim are daemons: they run in the background
until the block ends. `knoblab ctl --watch` without --count is stopped with Ctrl-C
(SIGINT) after a few seconds, as the transcript shows.
"""
import argparse
import os
import pathlib
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

COMMAND_TIMEOUT_S = 300
WATCH_SECONDS = 3


def blocks(path):
    """(line number, directive, [logical lines]) for each ```sh block."""
    lines = path.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        if lines[i].strip() == "```sh":
            start = i + 1
            j = i - 1
            while j >= 0 and not lines[j].strip():
                j -= 1
            m = re.match(r"<!--\s*doc-test:\s*(.*?)\s*-->", lines[j]) if j >= 0 else None
            body = []
            i += 1
            while i < len(lines) and lines[i].strip() != "```":
                body.append(lines[i])
                i += 1
            yield start, (m.group(1) if m else ""), commands(body)
        i += 1


def commands(body):
    transcript = any(l.startswith("$ ") for l in body)
    out, pending = [], None
    for line in body:
        if pending is not None:
            pending += "\n" + line
        elif transcript:
            if not line.startswith("$ "):
                continue
            pending = line[2:]
        else:
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            pending = line
        if not pending.rstrip().endswith("\\"):
            out.append(pending)
            pending = None
    if pending is not None:
        out.append(pending)
    return out


def as_run_here(command, scratch, build):
    """The command as it runs inside the sysroot, or None when it is interactive."""
    command = re.sub(r"(?<![\w.])\./run knoblab\b", "knoblab", command)
    if re.match(r"^\./run shell\s*(#.*)?$", command):
        return None
    command = re.sub(r"^\./run shell\s+", "", command)
    if command.startswith("./run"):
        raise ValueError("cannot run '%s' inside the test; mark the block 'doc-test: skip REASON'" % command)
    # /tmp first: the build directory itself may lie under /tmp.
    command = command.replace("/tmp/", str(scratch) + "/")
    return re.sub(r"(?<![\w/.])build/", str(build) + "/", command)


def is_daemon(command):
    first = command.split()[0]
    name = os.path.basename(first)
    return (name == "hapticd" and "--cycles" not in command) or name == "knoblab-modbus-sim"


class Block:
    def __init__(self, where, env, scratch):
        self.where, self.env, self.scratch = where, env, scratch
        self.daemons = []
        self.failures = []

    def start_daemon(self, command):
        log = open(self.scratch / ("daemon-%d.log" % len(self.daemons)), "w+")
        p = subprocess.Popen(["bash", "-c", "exec " + command], cwd=self.scratch, env=self.env,
                             stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        self.daemons.append((command, p, log))
        # Up: its control socket exists, or (without one) it is still running after a second.
        socket = re.search(r"--socket\s+(\S+)", command)
        deadline = time.monotonic() + (20 if socket else 1)
        while time.monotonic() < deadline and p.poll() is None:
            if socket and os.path.exists(socket.group(1)):
                break
            time.sleep(0.05)
        print("  $ %s &  -> %s" % (command.replace("\n", " "), "running" if p.poll() is None else "ended"))
        if p.poll() is not None:
            log.seek(0)
            self.failures.append("%s: daemon '%s' ended at once (exit %s):\n%s" %
                                 (self.where, command, p.returncode, log.read()[-2000:]))

    def run(self, command):
        if is_daemon(command):
            return self.start_daemon(command)
        watch = "--watch" in command and "--count" not in command
        p = subprocess.Popen(["bash", "-c", command], cwd=self.scratch, env=self.env,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             start_new_session=True)
        try:
            out, err = p.communicate(timeout=WATCH_SECONDS if watch else COMMAND_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGINT if watch else signal.SIGKILL)
            out, err = p.communicate()
            if not watch:
                self.failures.append("%s: '%s' took over %d s" % (self.where, command, COMMAND_TIMEOUT_S))
                return
        print("  $ %s  -> exit %d" % (command.replace("\n", " "), p.returncode))
        if p.returncode != 0:
            self.failures.append("%s: '%s' exited %d\n--- stdout\n%s\n--- stderr\n%s" %
                                 (self.where, command, p.returncode, out[-2000:], err[-2000:]))

    def stop(self):
        for command, p, log in self.daemons:
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGTERM)
                try:
                    p.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    os.killpg(p.pid, signal.SIGKILL)
                    p.wait()
                    self.failures.append("%s: daemon '%s' ignored SIGTERM" % (self.where, command))
            log.close()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repo", required=True, type=pathlib.Path)
    ap.add_argument("--build", required=True, type=pathlib.Path)
    ap.add_argument("--only", help="run only the blocks of this file (relative to the repository)")
    args = ap.parse_args()
    repo, build = args.repo.resolve(), args.build.resolve()
    docs = [repo / "README.md"] + sorted((repo / "docs").glob("*.md"))
    if args.only:
        docs = [repo / args.only]
    failures, ran, skipped = [], 0, 0
    for doc in docs:
        for line, directive, cmds in blocks(doc):
            where = "%s:%d" % (doc.relative_to(repo), line)
            if directive.startswith("skip"):
                print("%s: skipped (%s)" % (where, directive[4:].strip() or "no reason given"))
                if not directive[4:].strip():
                    failures.append("%s: a skipped block must say why" % where)
                skipped += 1
                continue
            scratch = pathlib.Path(tempfile.mkdtemp(prefix="knoblab-doc-"))
            env = dict(os.environ)
            env["PATH"] = os.pathsep.join(str(build / "apps" / d) for d in ("cli", "hapticd", "modbus")) + \
                os.pathsep + env.get("PATH", "/usr/bin:/bin")
            env["KNOBLAB_SOCKET"] = str(scratch / "hapticd.sock")
            block = Block(where, env, scratch)
            print("%s:" % where)
            try:
                for d in filter(None, (p.strip() for p in directive.split(";"))):
                    if d.startswith("with "):
                        source = (repo / d[5:].strip()).resolve()
                        if not source.is_dir():
                            raise ValueError("'with %s': no such directory" % d[5:].strip())
                        for entry in source.iterdir():
                            (scratch / entry.name).symlink_to(entry)
                    elif d == "hapticd":
                        block.start_daemon("hapticd --backend sim --rate 1000 --socket %s --telemetry "
                                           "/knoblab-doc-%d --db %s" % (env["KNOBLAB_SOCKET"], os.getpid(),
                                                                        scratch / "lab.sqlite"))
                    else:
                        raise ValueError("unknown directive '%s'" % d)
                for c in cmds:
                    here = as_run_here(c, scratch, build)
                    if here is not None:
                        block.run(here)
                        ran += 1
            except ValueError as e:
                block.failures.append("%s: %s" % (where, e))
            finally:
                block.stop()
                failures += block.failures
                shutil.rmtree(scratch, ignore_errors=True)
    print("\n%d commands run, %d blocks skipped" % (ran, skipped))
    for f in failures:
        print("FAIL " + f, file=sys.stderr)
    return 1 if failures or ran == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
