#!/usr/bin/env python3
"""Writes the message reference (Markdown) from the wire contract itself,
lcmtypes/rbsim/*.lcm: every type with its comment, every field with its type
and its comment (which gives its unit and frame), every constant. Run at
build time (target rbsim_message_reference -> build/docs/messages.md), so the
reference never drifts from the .lcm files; a field without a comment fails
the build.

    message_reference.py OUT.md FILE.lcm...
"""

import os
import re
import sys

FIELD = re.compile(r"^(?P<type>[A-Za-z_][\w.]*)\s+(?P<name>\w+)(?P<dims>(\s*\[[^\]]+\])*)\s*;$")
CONST = re.compile(r"^const\s+(?P<type>\w+)\s+(?P<items>.+);$")
STRUCT = re.compile(r"^struct\s+(?P<name>\w+)")


def parse(path):
    """(name, comment, [(kind, type, name, dims, comment)]) of one .lcm file."""
    with open(path, encoding="utf-8") as f:
        lines = [line.strip() for line in f]
    struct_name, struct_comment, members = None, "", []
    # A declaration without a comment of its own, right under another (no
    # blank line between), shares that one's: "// The client and seq ...".
    pending, shared = [], None
    statement = ""
    for line in lines:
        if line.startswith("//"):
            pending.append(line[2:].strip())
            continue
        if not line:
            if struct_name is None and pending:
                pending.append("")  # paragraph break in the type's comment
            shared = None
            continue
        if struct_name is None:
            match = STRUCT.match(line)
            if match:
                struct_name = match.group("name")
                struct_comment = "\n".join(pending).strip()
                pending = []
            elif not line.startswith("package"):
                pending = []
            continue
        if line in ("{", "}"):
            continue
        statement = (statement + " " + line).strip()
        if not statement.endswith(";"):
            continue  # a declaration over several lines
        comment = " ".join(p for p in pending if p).strip()
        pending = []
        const = CONST.match(statement)
        field = FIELD.match(statement)
        if not comment and shared:
            comment = shared
        shared = comment
        if const:
            items = " ".join(const.group("items").split())
            members.append(("const", const.group("type"), items, "", comment))
        elif field:
            members.append(("field", field.group("type"), field.group("name"),
                            field.group("dims").replace(" ", ""), comment))
        else:
            raise SystemExit("%s: cannot read the declaration '%s'" % (path, statement))
        statement = ""
    if struct_name is None:
        raise SystemExit("%s: no struct" % path)
    return struct_name, struct_comment, members


def markdown(types):
    out = ["# rbsim messages", "",
           "Generated from `lcmtypes/rbsim/*.lcm` at build time (`lcmtypes/message_reference.py`): "
           "the wire contract's own comments, which give every unit and frame. SI units; the world "
           "frame is right-handed with z up; quaternions are (w, x, y, z).", ""]
    out += ["| type | first line |", "| --- | --- |"]
    for name, comment, _ in types:
        paragraph = " ".join(comment.split("\n\n")[0].split())
        first = re.split(r"(?<=\.)\s", paragraph)[0]
        out.append("| [`%s`](#%s) | %s |" % (name, name, first.replace("|", "\\|")))
    for name, comment, members in types:
        out += ["", "## %s" % name, "", comment, "", "| field | type | meaning |", "| --- | --- | --- |"]
        for kind, type_, member, dims, text in members:
            label = "`%s`" % member if kind == "field" else "const `%s`" % member
            out.append("| %s | `%s%s` | %s |" % (label, type_, dims, text.replace("|", "\\|")))
    return "\n".join(out) + "\n"


def main(argv):
    if len(argv) < 3:
        raise SystemExit(__doc__)
    types = [parse(path) for path in sorted(argv[2:])]
    missing = ["%s.%s" % (name, member) for name, _, members in types
               for kind, _, member, _, text in members if kind == "field" and not text]
    if missing:
        raise SystemExit("message_reference: fields without a comment (unit, frame, meaning): %s"
                         % ", ".join(missing))
    os.makedirs(os.path.dirname(os.path.abspath(argv[1])), exist_ok=True)
    with open(argv[1], "w", encoding="utf-8") as f:
        f.write(markdown(types))


if __name__ == "__main__":
    main(sys.argv)
