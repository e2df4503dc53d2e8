"""The message reference generated from lcmtypes/rbsim/*.lcm documents every
field of every type, and the build refuses a field without a comment."""

import glob
import os
import re
import subprocess

from conftest import BUILD, PYTHON, REPO

GENERATOR = os.path.join(REPO, "lcmtypes", "message_reference.py")
LCM_FILES = sorted(glob.glob(os.path.join(REPO, "lcmtypes", "rbsim", "*.lcm")))


def _fields(path):
    """Field names of a .lcm file, read independently of the generator."""
    with open(path) as f:
        text = re.sub(r"//[^\n]*", "", f.read())
    body = text[text.index("{") + 1:text.rindex("}")]
    names = []
    for statement in body.split(";"):
        words = statement.split()
        if words and words[0] != "const":
            names.append(re.sub(r"\[.*", "", words[1]))
    return names


def test_every_field_of_every_type_is_in_the_reference(tmp_path):
    out = tmp_path / "messages.md"
    subprocess.run([PYTHON, GENERATOR, str(out)] + LCM_FILES, check=True)
    text = out.read_text()
    for path in LCM_FILES:
        name = os.path.basename(path)[:-4]
        section = text.split("\n## %s\n" % name, 1)[1].split("\n## ", 1)[0]
        for field in _fields(path):
            row = re.search(r"^\| `%s` \| `[^`]+` \| (.+) \|$" % re.escape(field), section, re.M)
            assert row and row.group(1).strip(), "%s.%s has no description in the reference" % (name, field)
    assert "| `wrenches_cleared` | `int32_t` |" in text
    # The build's copy is the same.
    built = os.path.join(BUILD, "docs", "messages.md")
    if os.path.exists(built):
        with open(built) as f:
            assert f.read() == text, "build/docs/messages.md is stale: rebuild"


def test_a_field_without_a_comment_fails(tmp_path):
    bad = tmp_path / "bad_t.lcm"
    bad.write_text("package rbsim;\n\n// A type.\nstruct bad_t\n{\n  // s\n  double t;\n\n  int32_t mystery;\n}\n")
    proc = subprocess.run([PYTHON, GENERATOR, str(tmp_path / "out.md"), str(bad)], capture_output=True, text=True)
    assert proc.returncode != 0 and "bad_t.mystery" in proc.stderr, proc.stderr
