#!/usr/bin/env python3
"""Fails when a source file includes a header of a room it may not include.

The rooms and their allowed includes are the `include-rules` block of docs/architecture.md, the
one place they are written. Every quoted #include of every C++ file under the rooms is resolved
the way the build resolves it (the including file's folder, then engine/, server/, include/,
bench/, tests/, tests/server/) and the file's room must list the header's room (or be it). A file in no room is
an error too, so a new folder has to be placed in the picture.

usage: check_includes.py ROOT            check the tree at ROOT
       check_includes.py ROOT --self-test  also show that a back-include is caught
Debian's python3 only.
"""
import re
import shutil
import sys
import tempfile
from pathlib import Path

SEARCH_ROOTS = ["engine", "server", "include", "bench", "tests", "tests/server"]
GENERATED = {"openapi_yaml.inc", "rupture_schemas.inc", "rupture_build_commit.hpp", "rupture_build_flags.hpp",
             "rupture_validation_files.inc"}  # written by the build, not in the tree
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def read_rules(root):
    text = (root / "docs" / "architecture.md").read_text(encoding="utf-8")
    block = re.search(r"```include-rules\n(.*?)```", text, re.S)
    if not block:
        sys.exit("docs/architecture.md has no ```include-rules block")
    rules = {}
    for line in block.group(1).splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        room, _, allowed = line.partition(":")
        rules[room.strip()] = [a for a in allowed.split() if a != "-"]
    return rules


def room_of(path, rooms):
    """The longest room that holds `path` (a path relative to the root, with / separators)."""
    best = None
    for room in rooms:
        if path == room or path.startswith(room + "/"):
            if best is None or len(room) > len(best):
                best = room
    return best


def resolve(root, source, include):
    for base in [source.parent] + [root / r for r in SEARCH_ROOTS]:
        candidate = (base / include).resolve()
        if candidate.is_file():
            return candidate
    return None


def check(root):
    rules = read_rules(root)
    problems = []
    sources = [p for r in rules if (root / r).exists()
               for p in ((root / r).rglob("*") if (root / r).is_dir() else [root / r])
               if p.suffix in (".hpp", ".cpp", ".h", ".inc")]
    for source in sorted(set(sources)):
        rel = source.relative_to(root).as_posix()
        room = room_of(rel, rules)
        for include in INCLUDE.findall(source.read_text(encoding="utf-8", errors="replace")):
            if Path(include).name in GENERATED:
                continue
            target = resolve(root, source, include)
            if target is None:
                problems.append(f"{rel}: #include \"{include}\" names no file in the tree")
                continue
            target_rel = target.relative_to(root.resolve()).as_posix()
            target_room = room_of(target_rel, rules)
            if target_room is None:
                problems.append(f"{rel}: #include \"{include}\" is in no room of docs/architecture.md")
            elif target_room != room and target_room not in rules[room] and "*" not in rules[room]:
                problems.append(f"{rel} ({room}) includes {target_rel} ({target_room}): "
                                f"{room} may include {' '.join(rules[room]) or 'no other room'}")
    return problems


def self_test(root):
    """A copy of the tree where the lowest engine room includes the scenarios: must fail."""
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / "tree"
        for part in ["docs", "engine", "server", "include", "bench", "tests"]:
            shutil.copytree(root / part, copy / part, ignore=shutil.ignore_patterns("*.h5", "__pycache__"))
        victim = sorted((copy / "engine" / "core").glob("*.hpp"))[0]
        scenario_header = sorted((copy / "engine" / "scenarios").rglob("*.hpp"))[0]
        include = scenario_header.relative_to(copy / "engine").as_posix()
        victim.write_text(f'#include "{include}"\n' + victim.read_text(encoding="utf-8"), encoding="utf-8")
        problems = check(copy)
        caught = any(victim.name in p and "engine/scenarios" in p for p in problems)
        print(f"self-test: {victim.relative_to(copy)} made to include {include}: "
              + ("caught" if caught else "NOT caught"))
        return caught


def main():
    root = Path(sys.argv[1]).resolve() if len(sys.argv) > 1 else Path(__file__).resolve().parents[2]
    problems = check(root)
    for p in problems:
        print(p)
    if "--self-test" in sys.argv and not self_test(root):
        return 1
    print(f"{len(problems)} include(s) against docs/architecture.md")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
