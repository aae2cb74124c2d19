#!/usr/bin/python3
"""The OpenJD template (scripts/farm/openjd_filter.yaml) checked against the
rules of the OpenJD 2023-09 template schema that apply to it (root, job
parameter, step, host requirement, task parameter, action and embedded file
objects: required keys, allowed keys, types, enumerations, identifiers,
name patterns, and every format string's references), then run the way an
OpenJD runtime runs it, on folders whose names have spaces, an apostrophe and
double quotes: every format string is substituted verbatim, the embedded
file written out, the task parameter's range expanded, and each task's
command run with its arguments as separate arguments (no shell), as the
spec does. Every frame must then be filtered, with the options given.

Usage: openjd_template_test.py AAF_EXECUTABLE TEMPLATE WORK_DIR"""
import os
import re
import shutil
import subprocess
import sys

import yaml

aaf, template_path, work = sys.argv[1:4]
aaf = os.path.abspath(aaf)
FORMAT = re.compile(r"\{\{\s*([A-Za-z0-9_.]+)\s*\}\}")
IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,63}")
errors = []


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



def check(condition, message):
    if not condition:
        errors.append(message)


def check_object(value, where, required, optional):
    """A mapping with every required key and no key the schema does not define."""
    if not isinstance(value, dict):
        errors.append("%s is not an object" % where)
        return False
    for key in required:
        check(key in value, "%s has no %s" % (where, key))
    for key in value:
        check(key in required or key in optional, "%s has %s, which the schema does not define" % (where, key))
    return True


def check_identifier(value, where):
    check(isinstance(value, str) and IDENTIFIER.fullmatch(value), "%s %r is not an <Identifier>" % (where, value))


def check_format_string(text, where, scope):
    """Each {{ expression }} names a value available in this scope (spec 7.3.1)."""
    if not isinstance(text, str):
        errors.append("%s is not a string" % where)
        return
    for name in FORMAT.findall(text):
        check(name in scope, "%s refers to {{%s}}, which is not available there" % (where, name))
    check(text.count("{{") == len(FORMAT.findall(text)), "%s has a malformed {{ expression }}" % where)


PARAMETER_KEYS = {
    "STRING": {"name", "type", "description", "default", "allowedValues", "minLength", "maxLength", "userInterface"},
    "PATH": {"name", "type", "description", "default", "allowedValues", "minLength", "maxLength", "objectType",
             "dataFlow", "userInterface"},
    "INT": {"name", "type", "description", "default", "allowedValues", "minValue", "maxValue", "userInterface"},
    "FLOAT": {"name", "type", "description", "default", "allowedValues", "minValue", "maxValue", "userInterface"},
}


def validate(template):
    """The 2023-09 schema's rules for the parts this template uses."""
    if not check_object(template, "the template", {"specificationVersion", "name", "steps"},
                        {"$schema", "description", "parameterDefinitions", "jobEnvironments"}):
        return {}
    check(template["specificationVersion"] == "jobtemplate-2023-09", "specificationVersion is not jobtemplate-2023-09")
    definitions = template.get("parameterDefinitions", [])
    check(isinstance(definitions, list) and 1 <= len(definitions) <= 50, "parameterDefinitions is not a list of 1-50")
    parameters = {}
    for i, p in enumerate(definitions):
        where = "parameterDefinitions[%d]" % i
        if not isinstance(p, dict) or p.get("type") not in PARAMETER_KEYS:
            errors.append("%s has no type STRING, PATH, INT or FLOAT" % where)
            continue
        check_object(p, where, {"name", "type"}, PARAMETER_KEYS[p["type"]])
        check_identifier(p.get("name"), where + " name")
        check(p.get("name") not in parameters, "%s repeats the name %s" % (where, p.get("name")))
        parameters[p.get("name")] = p
        if p["type"] in ("STRING", "PATH"):
            for key in ("default",):
                check(key not in p or (isinstance(p[key], str) and len(p[key]) <= 1024), "%s %s is not a string" % (where, key))
            for key in ("minLength", "maxLength"):
                check(key not in p or (type(p[key]) is int and p[key] >= 0), "%s %s is not a count" % (where, key))
            check("default" not in p or len(p["default"]) >= p.get("minLength", 0), "%s default is shorter than minLength" % where)
        if p["type"] == "PATH":
            check(p.get("objectType", "DIRECTORY") in ("FILE", "DIRECTORY"), "%s objectType is not FILE or DIRECTORY" % where)
            check(p.get("dataFlow", "NONE") in ("NONE", "IN", "OUT", "INOUT"), "%s dataFlow is not NONE, IN, OUT or INOUT" % where)
        if p["type"] == "INT":
            for key in ("default", "minValue", "maxValue"):
                check(key not in p or type(p[key]) is int or (isinstance(p[key], str) and re.fullmatch(r"-?\d+", p[key])),
                      "%s %s is not an integer" % (where, key))
            check("default" not in p or "minValue" not in p or int(p["default"]) >= int(p["minValue"]),
                  "%s default is below minValue" % where)
        if "allowedValues" in p:
            check(isinstance(p["allowedValues"], list) and p["allowedValues"], "%s allowedValues is not a list" % where)
            check("default" not in p or p["default"] in p["allowedValues"], "%s default is not an allowed value" % where)
    # Job-level format strings: every parameter but a PATH (spec 7.3.1).
    job_scope = {prefix + name for name, p in parameters.items() for prefix in ("Param.", "RawParam.")
                 if prefix == "RawParam." or p["type"] != "PATH"}
    check_format_string(template["name"], "the job name", job_scope)
    check(isinstance(template["name"], str) and 1 <= len(template["name"]) <= 128, "the job name is not 1-128 characters")
    steps = template["steps"]
    check(isinstance(steps, list) and steps, "steps is not a non-empty list")
    step_names = set()
    for i, step in enumerate(steps if isinstance(steps, list) else []):
        where = "steps[%d]" % i
        if not check_object(step, where, {"name", "script"}, {"description", "dependencies", "stepEnvironments",
                                                              "hostRequirements", "parameterSpace"}):
            continue
        check(isinstance(step["name"], str) and 1 <= len(step["name"]) <= 64, "%s name is not 1-64 characters" % where)
        check(step["name"] not in step_names, "%s repeats the step name %s" % (where, step["name"]))
        step_names.add(step["name"])
        host = step.get("hostRequirements")
        if host is not None and check_object(host, where + ".hostRequirements", set(), {"amounts", "attributes"}):
            check(host.get("amounts") or host.get("attributes"), "%s.hostRequirements has no amounts or attributes" % where)
            for j, amount in enumerate(host.get("amounts", [])):
                at = "%s.hostRequirements.amounts[%d]" % (where, j)
                check_object(amount, at, {"name"}, {"min", "max"})
                check(re.fullmatch(r"([A-Za-z_]\w*:)?amount(\.[A-Za-z_]\w*)+", str(amount.get("name"))),
                      "%s name %r is not an amount capability" % (at, amount.get("name")))
                check("min" in amount or "max" in amount, "%s has neither min nor max" % at)
                check(all(isinstance(amount.get(k, 0), (int, float)) and amount.get(k, 0) >= 0 for k in ("min", "max")),
                      "%s min or max is not a non-negative number" % at)
                if str(amount.get("name")).lower() == "amount.worker.vcpu":
                    check(amount.get("min", 1) >= 1, "%s asks for under 1 vCPU" % at)
            for j, attribute in enumerate(host.get("attributes", [])):
                at = "%s.hostRequirements.attributes[%d]" % (where, j)
                check_object(attribute, at, {"name"}, {"anyOf", "allOf"})
                check(re.fullmatch(r"([A-Za-z_]\w*:)?attr(\.[A-Za-z_]\w*)+", str(attribute.get("name"))),
                      "%s name %r is not an attribute capability" % (at, attribute.get("name")))
                check("anyOf" in attribute or "allOf" in attribute, "%s has neither anyOf nor allOf" % at)
                for value in attribute.get("anyOf", []) + attribute.get("allOf", []):
                    check(re.fullmatch(r"[A-Za-z_][A-Za-z0-9_-]{0,99}", str(value)), "%s value %r is not allowed" % (at, value))
                if str(attribute.get("name")).lower() == "attr.worker.os.family":
                    check(set(attribute.get("anyOf", [])) <= {"linux", "windows", "macos"}, "%s names an unknown OS family" % at)
        task_scope = set()
        space = step.get("parameterSpace")
        if space is not None and check_object(space, where + ".parameterSpace", {"taskParameterDefinitions"}, {"combination"}):
            tasks = space["taskParameterDefinitions"]
            check(isinstance(tasks, list) and 1 <= len(tasks) <= 16, "%s has not 1-16 task parameters" % where)
            for j, t in enumerate(tasks):
                at = "%s.parameterSpace.taskParameterDefinitions[%d]" % (where, j)
                check_object(t, at, {"name", "type", "range"}, set())
                check_identifier(t.get("name"), at + " name")
                check(t.get("type") in ("INT", "FLOAT", "STRING", "PATH"), "%s type is not INT, FLOAT, STRING or PATH" % at)
                check(isinstance(t.get("range"), (str, list)), "%s range is not a range expression or a list" % at)
                if isinstance(t.get("range"), str):
                    check_format_string(t["range"], at + " range", job_scope)
                task_scope |= {"Task.Param." + str(t.get("name")), "Task.RawParam." + str(t.get("name"))}
        script = step["script"]
        if not check_object(script, where + ".script", {"actions"}, {"embeddedFiles"}):
            continue
        files = script.get("embeddedFiles", [])
        check(isinstance(files, list) and (files or "embeddedFiles" not in script), "%s embeddedFiles is empty" % where)
        for j, embedded in enumerate(files):
            at = "%s.script.embeddedFiles[%d]" % (where, j)
            check_object(embedded, at, {"name", "type", "data"}, {"filename", "runnable"})
            check_identifier(embedded.get("name"), at + " name")
            check(embedded.get("type") == "TEXT", "%s type is not TEXT" % at)
            check(isinstance(embedded.get("runnable", False), bool), "%s runnable is not a boolean" % at)
            check("filename" not in embedded or re.fullmatch(r"[^/\\]{1,64}", str(embedded["filename"])),
                  "%s filename is not a base name of 1-64 characters" % at)
            task_scope.add("Task.File." + str(embedded.get("name")))
        script_scope = job_scope | {"Param." + n for n in parameters} | task_scope | {
            "Session.WorkingDirectory", "Session.HasPathMappingRules", "Session.PathMappingRulesFile"}
        actions = script["actions"]
        if check_object(actions, where + ".script.actions", {"onRun"}, set()):
            on_run = actions["onRun"]
            at = where + ".script.actions.onRun"
            if check_object(on_run, at, {"command"}, {"args", "timeout", "cancelation"}):
                check(isinstance(on_run["command"], str) and on_run["command"], "%s command is empty" % at)
                check_format_string(on_run["command"], at + " command", script_scope)
                check(isinstance(on_run.get("args", []), list), "%s args is not a list" % at)
                for k, arg in enumerate(on_run.get("args", [])):
                    check_format_string(arg, "%s args[%d]" % (at, k), script_scope)
                cancel = on_run.get("cancelation", {"mode": "TERMINATE"})
                check(cancel.get("mode") in ("TERMINATE", "NOTIFY_THEN_TERMINATE"), "%s cancelation mode is unknown" % at)
                check(type(cancel.get("notifyPeriodInSeconds", 1)) is int and 1 <= cancel.get("notifyPeriodInSeconds", 1) <= 600,
                      "%s notifyPeriodInSeconds is not 1-600" % at)
        for j, embedded in enumerate(files):
            check_format_string(embedded.get("data"), "%s.script.embeddedFiles[%d] data" % (where, j), script_scope)
            # A text parameter pasted into a script is code: it must come as an argument.
            for name, p in parameters.items():
                check(not (p["type"] in ("STRING", "PATH") and
                           re.search(r"\{\{\s*(Raw)?Param\.%s\s*\}\}" % name, str(embedded.get("data")))),
                      "the embedded file %s pastes Param.%s into its text" % (embedded.get("name"), name))
    return parameters


with open(template_path) as f:
    template = yaml.safe_load(f)
parameters = validate(template)
if errors:
    fail("the template breaks the 2023-09 schema:\n  " + "\n  ".join(errors))
for name, flow, kind in (("InputDirectory", "IN", "DIRECTORY"), ("OutputDirectory", "OUT", "DIRECTORY"),
                         ("AafExecutable", "NONE", "FILE")):
    p = parameters.get(name, {})
    if p.get("type") != "PATH" or p.get("dataFlow") != flow or p.get("objectType") != kind:
        fail("%s is not a PATH parameter of objectType %s, dataFlow %s" % (name, kind, flow))
step = template["steps"][0]
on_run = step["script"]["actions"]["onRun"]
files = step["script"].get("embeddedFiles", [])

shutil.rmtree(work, ignore_errors=True)
shot = os.path.join(work, "it's a \"shot\" $HOME `x`")
os.makedirs(shot)
subprocess.run([aaf, "render", "grids", "--frames", "1-3", "-o", os.path.join(shot, "noisy.####.exr"),
                "--width", "16", "--height", "12", "--spp", "2", "--progress", "none"], check=True)
outputs = os.path.join(shot, "out \"filtered\"")
values = {"Param.AafExecutable": aaf, "Param.InputDirectory": shot, "Param.InputName": "noisy.####.exr",
          "Param.OutputDirectory": outputs, "Param.OutputName": "aaf.####.exr", "Param.Method": "aaf",
          "Param.FilterOptions": "--mu 2.5 --map position=P", "Param.FirstFrame": 1, "Param.LastFrame": 3,
          "Param.ChunkSize": 2}
for name, p in parameters.items():
    values.setdefault("Param." + name, p.get("default"))
    values["RawParam." + name] = values["Param." + name]
task_parameter = step["parameterSpace"]["taskParameterDefinitions"][0]
chunks = expand_range(substitute(task_parameter["range"], values))
if chunks != [1, 3]:
    fail("the chunks of 1-3 by 2 are %s" % chunks)
for chunk in chunks:
    session = os.path.join(work, "session_%d" % chunk)
    os.makedirs(session)
    task_values = {**values, "Task.Param." + task_parameter["name"]: chunk,
                   "Session.WorkingDirectory": session}
    for embedded in files:
        path = os.path.join(session, embedded["name"])
        with open(path, "w") as f:
            f.write(substitute(embedded["data"], task_values))
        task_values["Task.File." + embedded["name"]] = path
    command = [substitute(on_run["command"], task_values)] + [substitute(a, task_values) for a in on_run["args"]]
    run = subprocess.run(command, env={k: v for k, v in os.environ.items() if k != "AAF"},
                         capture_output=True, text=True, cwd=session)
    if run.returncode != 0:
        fail("task %d exited %d: %s" % (chunk, run.returncode, run.stderr.strip()))
    if "openjd_progress:" not in run.stdout + run.stderr:
        fail("task %d reported no openjd_progress" % chunk)
for frame in (1, 2, 3):
    if not os.path.isfile(os.path.join(outputs, "aaf.%04d.exr" % frame)):
        fail("frame %d in %r was not filtered" % (frame, outputs))
# The options reached aaf: the same bytes as a local run with them.
local = os.path.join(work, "local")
os.makedirs(local)
subprocess.run([aaf, "filter", "aaf", os.path.join(shot, "noisy.####.exr"), "-o", os.path.join(local, "aaf.####.exr"),
                "--frames", "1-3", "--progress", "none", "--mu", "2.5", "--map", "position=P"], check=True)
for frame in (1, 2, 3):
    with open(os.path.join(outputs, "aaf.%04d.exr" % frame), "rb") as a, \
            open(os.path.join(local, "aaf.%04d.exr" % frame), "rb") as b:
        if a.read() != b.read():
            fail("frame %d differs from a local aaf filter run with the same options" % frame)
print("OK: the template keeps the 2023-09 schema's rules; its tasks filtered every frame in %r" % outputs)
