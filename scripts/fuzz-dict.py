#!/usr/bin/env python3
"""Writes tests/fuzz/gbx.dict: the grammar's keywords and punctuation, and the catalogue's
attribute, setting, effect, method and unit names, as a libFuzzer dictionary."""
import glob
import os
import re

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
word = re.compile(r"^[A-Za-z_][A-Za-z0-9_.]*$")
words = set()
for m in re.finditer(r"'([^'\\\s]+)'", open(os.path.join(root, "grammar/Gbx.g4")).read()):
    words.add(m.group(1))
sources = glob.glob(os.path.join(root, "compiler/catalogue/*")) + [os.path.join(root, "compiler/units/Unit.cpp")]
for f in sources:
    for m in re.finditer(r'"([^"\s]{1,32})"', open(f).read()):
        w = m.group(1)
        if (word.match(w) or re.match(r"^[A-Za-z0-9_^*/.]+$", w)) and not w.endswith(".h"):
            words.add(w)
words.update(["mesh_period", "mesh_periods", "N*m", "+-", "..", "1e-12", "1e308", "0 / 0", "1000000000",
              "import materials;", "import modules;", "import gleason;", "import klingelnberg;", " // ", "/*", "*/"])
with open(os.path.join(root, "tests/fuzz/gbx.dict"), "w") as out:
    out.write("# The .gbx language for libFuzzer (scripts/fuzz-dict.py writes this file): the grammar's\n"
              "# keywords and punctuation, the catalogue's attribute, setting, effect, method and unit names.\n")
    for w in sorted(words):
        out.write('"%s"\n' % w.replace("\\", "\\\\").replace('"', '\\"'))
print(len(words), "entries")
