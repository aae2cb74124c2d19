#!/usr/bin/python3
"""Every code name a design page cites exists in the code.

Usage: test_doc_names.py SOURCE_DIR PAGE.md [PAGE.md ...]

A design page (the architecture note) names functions, types, files and
folders in `backticks` so that a reader can find them. This reads every
backticked span of each page and checks it: a path (containing '/' or ending
in a source or Markdown suffix) must exist under SOURCE_DIR (relative to the
repository, or to the page's own folder); an identifier (a word with '_' or
'::' or an inner capital, optionally followed by '()') must occur as a whole
word in a C++, Python or CMake file under libaaf/, cli/, tests/ or scripts/.
Command lines, options, placeholders (`<name>`) and plain words are not
checked. Exits 1 listing
every page, line and name that is missing."""
import os
import re
import sys

source_dir, pages = sys.argv[1], sys.argv[2:]
code_suffixes = (".cpp", ".h", ".py", ".txt", ".cmake", ".sh")
corpus = []
for top in ("libaaf", "cli", "tests", "scripts"):
    for root, _, files in os.walk(os.path.join(source_dir, top)):
        for name in files:
            if name.endswith(code_suffixes):
                with open(os.path.join(root, name), errors="replace") as f:
                    corpus.append(f.read())
corpus = "\n".join(corpus)

identifier = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_~][A-Za-z0-9_]*)*(\(\))?$")


def is_code_name(span):
    if not identifier.match(span):
        return False
    word = span.rstrip("()")
    return "::" in word or "_" in word or span.endswith("()") or re.search(r"[a-z][A-Z]", word)


def exists_in_code(span):
    word = span.rstrip("()")
    # a qualified name counts when its last part is defined or used in the code
    last = word.split("::")[-1]
    return re.search(r"(?<![A-Za-z0-9_])" + re.escape(last) + r"(?![A-Za-z0-9_])", corpus) is not None


def is_path(span):
    return " " not in span and ("/" in span or span.endswith(code_suffixes + (".md", ".json", ".yaml")))


missing = []
for page in pages:
    with open(page) as f:
        text = f.read()
    text = re.sub(r"^```.*?^```", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S | re.M)
    for number, line in enumerate(text.split("\n"), 1):
        for span in re.findall(r"`([^`]+)`", line):
            span = span.strip()
            if span.startswith(("-", "aaf ", "$")) or "<" in span:  # commands, options, placeholders
                continue
            if is_path(span):
                path = span.rstrip("/")
                candidates = [os.path.join(source_dir, path), os.path.join(os.path.dirname(page), path)]
                if not any(os.path.exists(c) for c in candidates):
                    missing.append(f"{page}:{number}: no such file or folder: {span}")
            elif is_code_name(span) and not exists_in_code(span):
                missing.append(f"{page}:{number}: no such name in the code: {span}")

for line in missing:
    print(line)
sys.exit(1 if missing else 0)
