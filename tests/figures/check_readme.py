#!/usr/bin/env python3
"""Runs the shell transcripts of README.md and checks the digits they print.

A ```console block holds commands `$ CMD` (a trailing `\\` continues it on the next line) and
the output shown after each, up to the next `$ ` line. Commands run with bash in one scratch
folder per block that sees the repository's data/ (a symbolic link); `build/bin/coatcontact`
and `build/...` are replaced by the program and the build folder under test.
Checks, per shown output line (in order, against the command's stdout and stderr together):
  - a line `...` skips any number of real lines (truncation);
  - `# columns:` lines compare their names exactly (tabs or spaces);
  - every other line: its words must equal the real line's, numbers to kRelTol relative
    (plus kAbsTol absolute), so that a printed digit that no longer reproduces fails.
  - a header line of error estimates (`error_estimate` columns, `... error estimate ...`)
    compares only its order of magnitude: such estimates move with the refinement path.
Each command must exit 0. Python blocks are not run here (python/tests runs the examples).

usage: check_readme.py --cli PATH/coatcontact --build BUILD_DIR README.md
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

kRelTol = 1e-7
kAbsTol = 1e-12
NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def blocks(text):
    out, inside, current = [], False, []
    for line in text.splitlines():
        if line.startswith("```"):
            if inside:
                out.append(current)
                inside = False
            elif line.strip() == "```console":
                inside, current = True, []
            continue
        if inside:
            current.append(line)
    return out


def commands(block):
    """(command, shown output lines) of a console block."""
    out, i = [], 0
    while i < len(block):
        line = block[i]
        if not line.startswith("$ "):
            raise SystemExit("output without a command: %r" % line)
        cmd = line[2:]
        while cmd.endswith("\\"):
            i += 1
            cmd = cmd[:-1] + " " + block[i].strip()
        i += 1
        shown = []
        while i < len(block) and not block[i].startswith("$ "):
            shown.append(block[i])
            i += 1
        out.append((cmd, shown))
    return out


def words_match(shown, real, estimate):
    a, b = shown.replace("\t", " ").split(), real.replace("\t", " ").split()
    if len(a) != len(b):
        return False
    for x, y in zip(a, b):
        xs, ys = x.rstrip(",;)"), y.rstrip(",;)")
        if NUMBER.match(xs) and NUMBER.match(ys):
            u, v = float(xs), float(ys)
            if estimate:  # an error estimate: the same order of magnitude
                if (u == 0) != (v == 0) or (u and abs(math.log10(abs(u) / abs(v))) > 1):
                    return False
            elif abs(u - v) > kRelTol * max(abs(u), abs(v)) + kAbsTol:
                return False
        elif x != y:
            return False
    return True


def check(shown, real):
    """None if the shown lines match the real ones, else a message."""
    j = 0
    skipping = False
    for line in shown:
        if line.strip() == "...":
            skipping = True
            continue
        while True:
            if j >= len(real):
                return "shown line not in the output: %r" % line
            candidate = real[j]
            j += 1
            if line.startswith("# columns:"):
                ok = candidate.startswith("# columns:") and line.split() == candidate.split()
            else:
                estimate = "error_estimate" in line or "error estimate" in line
                ok = words_match(line, candidate, estimate)
                if not ok and not line.startswith("#") and "error_estimate" in " ".join(real):
                    # the last column of a reduced row is its error estimate
                    lw, cw = line.split(), candidate.split()
                    ok = len(lw) == len(cw) and words_match(" ".join(lw[:-1]), " ".join(cw[:-1]), False) \
                        and words_match(lw[-1], cw[-1], True)
            if ok:
                skipping = False
                break
            if not skipping:
                return "line differs:\n  shown: %r\n  real:  %r" % (line, candidate)
    return None


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cli", required=True)
    parser.add_argument("--build", required=True)
    parser.add_argument("readme")
    args = parser.parse_args()
    source = os.path.dirname(os.path.abspath(args.readme))
    failures = ran = 0
    for block in blocks(open(args.readme, encoding="utf-8").read()):
        with tempfile.TemporaryDirectory() as scratch:
            os.symlink(os.path.join(source, "data"), os.path.join(scratch, "data"))
            for cmd, shown in commands(block):
                real_cmd = cmd.replace("build/bin/coatcontact", os.path.abspath(args.cli))
                real_cmd = re.sub(r"(?<![\w/])build/", os.path.abspath(args.build) + "/", real_cmd)
                p = subprocess.run(["bash", "-c", real_cmd], cwd=scratch, capture_output=True, text=True,
                                   timeout=600)
                ran += 1
                if p.returncode != 0:
                    print("FAIL (exit %d): %s\n%s" % (p.returncode, cmd, p.stderr[:500]))
                    failures += 1
                    continue
                problem = check(shown, (p.stdout + p.stderr).splitlines())
                if problem:
                    print("FAIL: %s\n  %s" % (cmd, problem))
                    failures += 1
                else:
                    print("ok   %s" % cmd[:100])
    print("%d commands, %d failed" % (ran, failures))
    return 1 if failures or ran == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
