#!/usr/bin/python3
"""Every option in the documentation's example commands exists.

Usage: test_doc_options.py AAF_EXECUTABLE PAGE.md [PAGE.md ...]

Reads each page's ```sh blocks, takes every command line that runs `aaf`
(continuation lines joined, comments dropped), and checks each `--option` it
uses against `aaf COMMAND --help` (`aaf filter METHOD --help`, `aaf analyze
wedge --help`): a renamed or removed option fails here instead of in a
user's shell. Exits 1 naming every page, line and option that is missing."""
import re
import shlex
import subprocess
import sys

aaf_exe, pages = sys.argv[1], sys.argv[2:]
help_cache = {}


def help_text(words):
    key = tuple(words)
    if key not in help_cache:
        run = subprocess.run([aaf_exe] + words + ["--help"], capture_output=True, text=True, timeout=60)
        if run.returncode != 0:
            help_cache[key] = None
        else:
            help_cache[key] = run.stdout + run.stderr
    return help_cache[key]


def commands(text):
    """(line number, words) of every aaf command in the page's ```sh blocks."""
    for block in re.finditer(r"^```sh\n(.*?)^```", text, re.S | re.M):
        first_line = text.count("\n", 0, block.start(1)) + 1
        pending, start = "", None
        for offset, line in enumerate(block.group(1).split("\n")):
            if start is None:
                start = first_line + offset
            pending += line
            if pending.endswith("\\"):
                pending = pending[:-1] + " "
                continue
            try:
                words = shlex.split(pending, comments=True)
            except ValueError:
                words = pending.split("#")[0].split()
            # aaf is the program: the first word after any VAR=value
            # assignments (AAF_ISA=sse4.2 aaf ...), not a method's name
            # in another program's arguments (aaf_submit.sh ... filter aaf).
            program = 0
            while program < len(words) and re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[program]):
                program += 1
            if program < len(words) and (words[program] == "aaf" or words[program].endswith("/aaf")):
                yield start, words[program + 1:]
            pending, start = "", None


failures, checked = [], 0
for page in pages:
    text = open(page, encoding="utf-8").read()
    for line_no, words in commands(text):
        if not words or words[0].startswith("-"):
            continue
        command = [words[0]]
        if words[0] in ("filter", "analyze") and len(words) > 1 and not words[1].startswith("-"):
            command.append(words[1])
        helped = help_text(command)
        if helped is not None:
            helped += help_text([])  # --isa, --memory-limit-gb: any command takes them
        if helped is None:
            failures.append("%s:%d: `aaf %s --help` fails" % (page, line_no, " ".join(command)))
            continue
        for word in words[len(command):]:
            # `[--mu 2 --k 3]` and `--fixed-mu | --mu-from-spp` in synopses.
            option = word.strip("[]()|").split("=")[0]
            if not re.fullmatch(r"--[a-z0-9][a-z0-9-]*", option):
                continue
            checked += 1
            if not re.search(r"(^|[\s,\[])" + re.escape(option) + r"($|[\s,=\]])", helped, re.M):
                failures.append("%s:%d: `aaf %s` has no option %s" % (page, line_no, " ".join(command), option))

for failure in failures:
    print(failure)
print("%d options checked in %d pages, %d missing" % (checked, len(pages), len(failures)))
sys.exit(1 if failures or checked == 0 else 0)
