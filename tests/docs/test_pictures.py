#!/usr/bin/python3
"""The documentation's pictures exist, are shown, and come from the script.

Usage: test_pictures.py SOURCE_DIR

Every image a page links (`![...](path)` in README.md and the method pages)
exists; every PNG under libaaf/core/methods/*/pictures/ is written by
scripts/pictures/make_pictures.sh and shown by README.md and by its
method's page; every method folder with a page has a picture. Exits 1 listing every problem."""
import glob
import os
import re
import sys

root = sys.argv[1]
pages = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "libaaf/core/methods/*/README.md")))
script = open(os.path.join(root, "scripts/pictures/make_pictures.sh")).read()
problems = []
shown = {}
for page in pages:
    text = open(page).read()
    for link in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text):
        path = os.path.normpath(os.path.join(os.path.dirname(page), link))
        shown.setdefault(path, set()).add(page)
        if not os.path.isfile(path):
            problems.append(f"{os.path.relpath(page, root)}: no such picture {link}")
pictures = sorted(glob.glob(os.path.join(root, "libaaf/core/methods/*/pictures/*.png")))
if not pictures:
    problems.append("no pictures under libaaf/core/methods/*/pictures/")
for folder in sorted(glob.glob(os.path.join(root, "libaaf/core/methods/*/README.md"))):
    method = os.path.basename(os.path.dirname(folder))
    if not glob.glob(os.path.join(os.path.dirname(folder), "pictures", "*.png")):
        problems.append(f"libaaf/core/methods/{method} has a page but no picture")
for picture in pictures:
    method, name = picture.split(os.sep)[-3], os.path.basename(picture)
    if f"$methods/{method}/pictures/{name}" not in script:
        problems.append(f"{os.path.relpath(picture, root)} is not made by scripts/pictures/make_pictures.sh")
    for page in (os.path.join(root, "README.md"), os.path.join(root, f"libaaf/core/methods/{method}/README.md")):
        if page not in shown.get(os.path.normpath(picture), set()):
            problems.append(f"{os.path.relpath(picture, root)} is not shown by {os.path.relpath(page, root)}")
for problem in problems:
    print(problem)
print(f"{len(pictures)} pictures, {len(problems)} problems")
sys.exit(1 if problems else 0)
