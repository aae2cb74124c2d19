#!/usr/bin/python3
"""Runs every case of testdata/bad/cases.json through the `aaf` binary (or
the program the case names: `"program"` is one of PROGRAMS below: the
Python module through tests/bad_inputs/python_case.py, the farm and Blender
scripts), each in a fresh scratch copy of testdata/bad/files/, and checks
the README's promises for a bad input:

- the exit code the case expects (0 ok, 1 other, 2 usage, 3 input/IO, 4 check);
- on failure, stderr is exactly one `aaf: error: ...` line (warnings aside;
  each program has its own prefix, e.g. `aaf.Error:` for the module),
  naming the case's file or option when it lists one;
- a case that `warns` prints an `aaf: warning:` line naming that text;
- no crash (a signal or a sanitizer report), no hang (--timeout per case),
  peak memory under --max-rss-mb (and an RLIMIT_AS, so a runaway allocation
  fails fast instead of filling the machine);
- nothing left behind: no new file (output, temporary) unless the case says it
  `creates` it, every other input byte-identical, `removes` gone; a created
  file reads back (`aaf info --stats` exits 0).

Prints one line per case that is not clean, then the summary
`bad inputs: N tried, C clean, K crashes, H hangs, F wrong` (and how many
were skipped: Python cases without --python-module-dir, Blender cases
without Blender); exits 1 unless every case tried is clean. Usage:
  run_bad_inputs.py AAF CASES_JSON FILES_DIR SCRATCH [--jobs 2] [--timeout 20] [--max-rss-mb 1024]
                    [--address-limit-mb 4096] [--only SUBSTRING] [--python-module-dir DIR]
                    [--scripts-dir DIR] [--blender BLENDER]
"""
import argparse
import concurrent.futures
import hashlib
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import threading
import time

# A sanitizer's report (a sanitized build prints these and exits non-zero).
# Not "WARNING: AddressSanitizer failed to allocate": with
# allocator_may_return_null that is a std::bad_alloc, judged like one.
SANITIZER_MARKS = ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer", "UndefinedBehaviorSanitizer:", "runtime error:")

HERE = os.path.dirname(os.path.abspath(__file__))
PYTHON = "/usr/bin/python3"  # Debian's, with numpy and OpenImageIO (TOOLCHAIN trap 4)
# Environment a farm script reads: a case sets what it needs, nothing leaks in.
FARM_ENV = ("LAST_FRAME", "AAF", "SLURM_ARRAY_TASK_ID", "SLURM_ARRAY_TASK_STEP", "SLURM_CPUS_PER_TASK")


class Program:
    """How a case's program is run and what its error line looks like."""

    def __init__(self, errors, warnings=(), quiet=None, needs=None):
        self.errors = errors      # prefixes of its one error line
        self.warnings = warnings  # prefixes of lines that may come beside it
        self.quiet = quiet        # a regex of progress lines a successful run may print on stderr
        self.needs = needs        # the option it cannot run without (else its cases are skipped)

    def command(self, case, opts):
        name, args = case.get("program", "aaf"), case["args"]
        if name == "aaf":
            return [opts.aaf, *args]
        if name == "python":  # args: [CODE], run with aaf and numpy imported
            return [PYTHON, os.path.join(HERE, "python_case.py"), *args]
        if name == "aaf_complete":
            return [PYTHON, os.path.join(opts.scripts_dir, "blender", "aaf_complete.py"), *args]
        if name == "slurm_filter":
            return ["bash", os.path.join(opts.scripts_dir, "farm", "slurm_filter.sh"), *args]
        if name == "blender_bridge":  # args: what follows `--`
            return [opts.blender, "-b", "--factory-startup", "--python",
                    os.path.join(opts.scripts_dir, "blender", "aaf_bridge.py"), "--", *args]
        raise ValueError("unknown program %r" % name)

    def environment(self, case, opts):
        env = {k: v for k, v in os.environ.items() if k not in FARM_ENV}
        if case.get("program") == "python":
            env["PYTHONPATH"] = opts.python_module_dir
        if case.get("program") == "slurm_filter":
            env["AAF"] = opts.aaf
        env.update(case.get("env", {}))
        return env


PROGRAMS = {
    "aaf": Program(("aaf: error:",), ("aaf: warning:",)),
    "python": Program(("aaf.Error:", "aaf.InputError:"), needs="python_module_dir"),
    "aaf_complete": Program(("aaf_complete.py: error:",)),
    "slurm_filter": Program(("slurm_filter.sh: error:",), ("aaf: warning:",), quiet=r"frame \d+ \(\d+/\d+\): "),
    "blender_bridge": Program(("aaf-bridge: error:",), ("aaf-bridge: warning:",), needs="blender"),
}


def snapshot(root):
    """Relative path -> sha256 of every file under root (folders by their files)."""
    files = {}
    for folder, _, names in os.walk(root):
        for name in names:
            full = os.path.join(folder, name)
            with open(full, "rb") as f:
                files[os.path.relpath(full, root)] = hashlib.sha256(f.read()).hexdigest()
    return files


def limit_memory(limit_bytes):
    def apply():
        if limit_bytes:
            resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))
    return apply


def run_aaf(aaf, args, cwd, timeout, address_limit, command=None, env=None):
    """(exit code, or None on a timeout; stderr text; peak RSS in MB). Runs
    `command` instead of `aaf args` when given."""
    with open(os.path.join(cwd, os.pardir, os.path.basename(cwd) + ".stderr"), "w+b") as err:
        proc = subprocess.Popen(command or [aaf, *args], cwd=cwd, stdin=subprocess.DEVNULL,
                                stdout=subprocess.DEVNULL, stderr=err, env=env,
                                preexec_fn=limit_memory(address_limit), start_new_session=True)
        timer = threading.Timer(timeout, os.killpg, (proc.pid, signal.SIGKILL))
        timer.start()
        _, status, usage = os.wait4(proc.pid, 0)  # this child's own peak memory, unlike RUSAGE_CHILDREN
        timed_out = not timer.is_alive()
        timer.cancel()
        proc.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        text = err.read().decode("utf-8", "replace")
    return None if timed_out else proc.returncode, text, usage.ru_maxrss / 1024


def error_line_problems(case, code, stderr):
    program = PROGRAMS[case.get("program", "aaf")]
    lines = [l for l in stderr.splitlines() if l.strip()]
    other = [l for l in lines if not l.startswith(program.warnings or ("aaf: warning:",))]
    if code == 0:
        return ["stderr: %r" % l for l in other if not (program.quiet and re.match(program.quiet, l))]
    errors = [l for l in other if l.startswith(program.errors)]
    problems = []
    if len(errors) != 1 or len(other) != 1:
        problems.append("stderr is not one '%s' line: %r" % (program.errors[0], other[:4]))
    elif case.get("names") and case["names"] not in errors[0]:
        problems.append("error line does not name %r: %r" % (case["names"], errors[0]))
    return problems


def file_problems(case, before, after, aaf, scratch, timeout, address_limit):
    creates, removes = set(case.get("creates", [])), set(case.get("removes", []))
    problems = []
    for name in sorted(set(after) - set(before) - creates):
        problems.append("left %s" % name)
    for name in sorted(set(before) - set(after) - removes):
        problems.append("removed %s" % name)
    for name in sorted(set(before) & set(after) - creates):
        if before[name] != after[name]:
            problems.append("modified %s" % name)
    for name in sorted(creates):
        if name not in after:
            problems.append("did not write %s" % name)
        elif name.lower().endswith(".exr"):
            code, _, _ = run_aaf(aaf, ["info", "--stats", name], scratch, timeout, address_limit)
            if code != 0:
                problems.append("%s does not read back (aaf info --stats exits %s)" % (name, code))
    problems += ["did not remove %s" % n for n in sorted(removes) if n in after]
    return problems


def prepare(case, files, scratch):
    """The scratch copy, with the case's setup: `copy` {source: target} (into
    new folders too), `symlink` and `hardlink` {link: existing file}."""
    shutil.copytree(files, scratch)
    setup = case.get("setup", {})
    for kind, make in (("copy", shutil.copyfile), ("symlink", None), ("hardlink", os.link)):
        for source, target in setup.get(kind, {}).items():
            if kind != "copy":
                source, target = target, source
            os.makedirs(os.path.dirname(os.path.join(scratch, target)), exist_ok=True)
            if kind == "symlink":
                os.symlink(source, os.path.join(scratch, target))
            else:
                make(os.path.join(scratch, source), os.path.join(scratch, target))


def run_case(case, opts):
    """(verdict, detail): verdict is clean, crash, hang or wrong."""
    scratch = os.path.join(opts.scratch, "%03d" % case["index"])
    shutil.rmtree(scratch, ignore_errors=True)
    prepare(case, opts.files, scratch)
    before = snapshot(scratch)
    program = PROGRAMS[case.get("program", "aaf")]
    start = time.monotonic()
    code, stderr, rss_mb = run_aaf(opts.aaf, case["args"], scratch, opts.timeout, opts.address_limit,
                                   program.command(case, opts), program.environment(case, opts))
    seconds = time.monotonic() - start
    if code is None:
        return "hang", "no exit after %g s" % opts.timeout
    if code < 0 or any(mark in stderr for mark in SANITIZER_MARKS):
        first = next((l for l in stderr.splitlines() if any(m in l for m in SANITIZER_MARKS)), "")
        return "crash", "signal %d %s" % (-code, first) if code < 0 else first
    problems = []
    if code != case["exit"]:
        problems.append("exit %d, expected %d" % (code, case["exit"]))
    problems += error_line_problems(case, code, stderr)
    if case.get("warns") and not any(l.startswith("aaf: warning:") and case["warns"] in l
                                     for l in stderr.splitlines()):
        problems.append("no 'aaf: warning:' line naming %r" % case["warns"])
    if rss_mb > opts.max_rss_mb:
        problems.append("peak memory %.0f MB, more than %d MB" % (rss_mb, opts.max_rss_mb))
    problems += file_problems(case, before, snapshot(scratch), opts.aaf, scratch, opts.timeout,
                              opts.address_limit)
    if not problems:
        shutil.rmtree(scratch, ignore_errors=True)
        return "clean", "%.2f s" % seconds
    return "wrong", "; ".join(problems)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("aaf")
    parser.add_argument("cases")
    parser.add_argument("files")
    parser.add_argument("scratch")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=20.0, help="seconds per case")
    parser.add_argument("--address-limit-mb", type=int, default=4096,
                        help="RLIMIT_AS per case, so an unchecked size fails fast instead of filling memory; "
                             "0 for sanitizer builds (ASan reserves terabytes of address space)")
    parser.add_argument("--max-rss-mb", type=int, default=1024,
                        help="peak memory allowed per case: every input is a few KB, whatever its header declares")
    parser.add_argument("--only", default="", help="run the cases whose name contains this")
    parser.add_argument("--python-module-dir", default="",
                        help="where the module `aaf` was built (PYTHONPATH of the Python cases; else skipped)")
    parser.add_argument("--scripts-dir", default=os.path.join(HERE, os.pardir, os.pardir, "scripts"),
                        help="the project's scripts/ (farm and Blender scripts)")
    parser.add_argument("--blender", default=shutil.which("blender") or "",
                        help="Blender for the bridge's cases (default: blender on the PATH; else skipped)")
    opts = parser.parse_args()
    opts.address_limit = opts.address_limit_mb * 1024 * 1024
    opts.aaf, opts.files, opts.scratch, opts.scripts_dir = (
        os.path.abspath(p) for p in (opts.aaf, opts.files, opts.scratch, opts.scripts_dir))
    if opts.python_module_dir:
        opts.python_module_dir = os.path.abspath(opts.python_module_dir)
    with open(opts.cases) as f:
        cases = json.load(f)["cases"]
    for index, case in enumerate(cases):
        case["index"] = index
    cases = [c for c in cases if opts.only in c["name"]]
    runnable = [c for c in cases if not PROGRAMS[c.get("program", "aaf")].needs
                or getattr(opts, PROGRAMS[c.get("program", "aaf")].needs)]
    skipped, cases = len(cases) - len(runnable), runnable
    shutil.rmtree(opts.scratch, ignore_errors=True)
    os.makedirs(opts.scratch)
    counts = {"clean": 0, "crash": 0, "hang": 0, "wrong": 0}
    with concurrent.futures.ThreadPoolExecutor(max_workers=opts.jobs) as pool:
        results = list(pool.map(lambda c: (c, *run_case(c, opts)), cases))
    for case, verdict, detail in results:
        counts[verdict] += 1
        if verdict != "clean":
            defect = " [issue item %d]" % case["defect"] if case.get("defect") else ""
            print("%-5s %s%s: %s" % (verdict.upper(), case["name"], defect, detail))
    print("bad inputs: %d tried, %d clean, %d crashes, %d hangs, %d wrong%s" %
          (len(cases), counts["clean"], counts["crash"], counts["hang"], counts["wrong"],
           ", %d skipped (no Python module or Blender)" % skipped if skipped else ""))
    return 0 if counts["clean"] == len(cases) else 1


if __name__ == "__main__":
    sys.exit(main())
