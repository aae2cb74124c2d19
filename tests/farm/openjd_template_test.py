#!/usr/bin/python3
"""The OpenJD template (scripts/farm/openjd_filter.yaml) run the way an
OpenJD 2023-09 runtime runs it, on an input and output whose folder has an
apostrophe and a space: the template's shape is checked against the spec,
every format string ({{Param.X}}, {{Task.Param.X}}, {{Task.File.Run}}) is
substituted verbatim, the embedded file is written out, the task
parameter's range expression is expanded, and each task's command runs
with its arguments as separate arguments (no shell), as the spec does.
Every frame must then be filtered.

Usage: openjd_template_test.py AAF_EXECUTABLE TEMPLATE WORK_DIR"""
import os
import re
import shutil
import subprocess
import sys

import yaml

aaf, template_path, work = sys.argv[1:4]
FORMAT = re.compile(r"\{\{\s*([A-Za-z0-9_.]+)\s*\}\}")


def fail(message):
    sys.exit("FAILED: " + message)


def substitute(text, values):
    """A format string with every expression replaced by its value, verbatim (spec: Format Strings)."""
    def value(match):
        if match.group(1) not in values:
            fail("unknown expression {{%s}} in %r" % (match.group(1), text))
        return str(values[match.group(1)])
    return FORMAT.sub(value, text)


def expand_range(expression):
    """An INT range expression: comma-separated items START[-END[:STEP]]."""
    values = []
    for item in expression.split(","):
        m = re.fullmatch(r"\s*(-?\d+)(?:\s*-\s*(-?\d+)(?::(-?\d+))?)?\s*", item)
        if not m:
            fail("bad range expression %r" % expression)
        start, end, step = int(m[1]), int(m[2] or m[1]), int(m[3] or 1)
        values += list(range(start, end + 1, step))
    return values


with open(template_path) as f:
    template = yaml.safe_load(f)
if template.get("specificationVersion") != "jobtemplate-2023-09":
    fail("not a jobtemplate-2023-09 template")
parameters = {p["name"]: p for p in template["parameterDefinitions"]}
for p in parameters.values():
    if p["type"] not in ("STRING", "INT", "FLOAT", "PATH"):
        fail("parameter %s has type %s" % (p["name"], p["type"]))
step = template["steps"][0]
on_run = step["script"]["actions"]["onRun"]
if not isinstance(on_run.get("args", []), list) or not all(isinstance(a, str) for a in on_run.get("args", [])):
    fail("onRun args is not a list of strings")
files = step["script"].get("embeddedFiles", [])
for embedded in files:
    if embedded.get("type") != "TEXT" or not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", embedded["name"]):
        fail("embedded file %r is not a named TEXT file" % embedded)
    # A text parameter pasted into a script is code: it must come as an argument.
    for name, p in parameters.items():
        if p["type"] in ("STRING", "PATH") and re.search(r"\{\{\s*Param\.%s\s*\}\}" % name, embedded["data"]):
            fail("the embedded file %s pastes Param.%s into its text" % (embedded["name"], name))

shutil.rmtree(work, ignore_errors=True)
shot = os.path.join(work, "it's a shot")
os.makedirs(shot)
subprocess.run([aaf, "render", "grids", "--frames", "1-3", "-o", os.path.join(shot, "noisy.####.exr"),
                "--width", "16", "--height", "12", "--spp", "2", "--progress", "none"], check=True)
values = {"Param.Input": os.path.join(shot, "noisy.####.exr"), "Param.Output": os.path.join(shot, "aaf.####.exr"),
          "Param.FirstFrame": 1, "Param.LastFrame": 3, "Param.ChunkSize": 2}
for name, p in parameters.items():
    values.setdefault("Param." + name, p.get("default"))
task_parameter = step["parameterSpace"]["taskParameterDefinitions"][0]
chunks = expand_range(substitute(task_parameter["range"], values))
if chunks != [1, 3]:
    fail("the chunks of 1-3 by 2 are %s" % chunks)
for chunk in chunks:
    session = os.path.join(work, "session_%d" % chunk)
    os.makedirs(session)
    task_values = {**values, "Task.Param." + task_parameter["name"]: chunk}
    for embedded in files:
        path = os.path.join(session, embedded["name"])
        with open(path, "w") as f:
            f.write(substitute(embedded["data"], task_values))
        task_values["Task.File." + embedded["name"]] = path
    command = [substitute(on_run["command"], task_values)] + [substitute(a, task_values) for a in on_run["args"]]
    run = subprocess.run(command, env={**os.environ, "AAF": aaf}, capture_output=True, text=True)
    if run.returncode != 0:
        fail("task %d exited %d: %s" % (chunk, run.returncode, run.stderr.strip()))
    if "openjd_progress:" not in run.stdout + run.stderr:
        fail("task %d reported no openjd_progress" % chunk)
for frame in (1, 2, 3):
    if not os.path.isfile(os.path.join(shot, "aaf.%04d.exr" % frame)):
        fail("frame %d in %r was not filtered" % (frame, shot))
print("OK: the template's tasks filtered every frame in %r" % shot)
