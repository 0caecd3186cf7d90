#!/usr/bin/env python3
"""Runs every command of a Markdown tutorial and checks the output it shows.

Commands live in ```console blocks as lines `$ coatcontact ...` (a trailing `\\` continues a
command on the next line); they run in a scratch folder that sees the repository's data/. The
lines after a command (up to the next `$ ` line or the end of the block) are its shown output:
  - `# columns: ...` lines must equal the program's own `# columns:` line (tabs or spaces);
  - other `#` header lines are not compared (they hold error estimates that may differ in the
    last digits between machines);
  - every other line is a data line; the shown data lines must match the first data lines of
    the real output (blank lines included), up to a line `...` that marks truncation.
    Numbers agree to kRelTol relative (plus kAbsTol absolute; kRelTolZoneLocation for the
    Maugis-Dugdale commands, --lambda; kRelTolEstimate for the *_err columns), words exactly.
Each command must exit with status 0. Any other `$ ` command in a console block is an error,
so the tutorial cannot show a command that this test does not run.

usage: check_tutorial.py --cli PATH/coatcontact [--update] TUTORIAL.md
  --update  rewrites the shown outputs from real runs (keeps how many data lines each block
            shows, and whether it shows the full header), i.e. pastes real output.
"""
import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile

# The solver's default tolerance is 1e-8 relative (error_estimate <= 1e-8); results may move
# within it when the refinement path changes (compiler, thread count). 1e-7 catches any real
# change of the numbers while ignoring that.
kRelTol = 1e-7
# A Maugis-Dugdale pull-off (--lambda) is a minimum located by Brent to ~1e-7 relative in a_bar
# (THEORY.md section 13); the values read at that location (a_bar, m, D_load) then move by a few
# 1e-7 with the compiler's rounding (Release against the sanitizer build: 1.4e-7 in D_load).
kRelTolZoneLocation = 1e-6
kAbsTol = 1e-12
# Columns named *_err hold error estimates: differences of nearly equal interpolants, whose
# leading digits say what they mean and whose fourth moves with the compiler's rounding (the
# Maugis-Dugdale a_bar_load_err: 2e-6 relative, Release against the sanitizer build).
kRelTolEstimate = 1e-3
TRUNCATION = "..."


def parse_blocks(lines):
    """Yields (command_line_index, command, [output line indices]) for each console command."""
    in_block = False
    continuing = False
    current = None
    for i, line in enumerate(lines):
        stripped = line.rstrip("\n")
        if not in_block:
            if stripped.strip() == "```console":
                in_block = True
            continue
        if stripped.strip() == "```":
            if current:
                yield current
            current = None
            in_block = False
            continue
        if continuing:
            # A command continued with a trailing backslash, as in a shell.
            current = (current[0], current[1][:-1].rstrip() + " " + stripped.strip(), current[2])
            continuing = stripped.endswith("\\")
            continue
        if stripped.startswith("$ "):
            if current:
                yield current
            current = (i, stripped[2:], [])
            continuing = stripped.endswith("\\")
        elif current is not None:
            current[2].append(i)
        elif stripped.strip():
            raise ValueError("line %d: output before any command in a console block" % (i + 1))
    if in_block:
        raise ValueError("unterminated ```console block")


def run(cli, command, workdir):
    argv = shlex.split(command)
    if not argv or argv[0] != "coatcontact":
        raise ValueError("only `coatcontact ...` commands may appear: %r" % command)
    proc = subprocess.run([cli] + argv[1:], cwd=workdir, capture_output=True, text=True,
                          timeout=300)
    return proc.returncode, proc.stdout, proc.stderr


# A fit's stop reason ("small step", "no further decrease ...") can differ between builds
# (-O2 against -O3 moves the model by an ulp where the start is already the minimum); both
# mean converged, so the reason is not compared.
STOP_REASON = re.compile(r"converged \(.*\) after")


def tokens_match(shown, actual, rel_tol=kRelTol, names=()):
    """names: the columns' names, to compare *_err columns at kRelTolEstimate."""
    shown, actual = (STOP_REASON.sub("converged after", x) for x in (shown, actual))
    a, b = shown.split(), actual.split()
    if len(a) != len(b):
        return False
    for k, (x, y) in enumerate(zip(a, b)):
        if x == y:
            continue
        tol = kRelTolEstimate if k < len(names) and names[k].endswith("_err") else rel_tol
        try:
            fx, fy = float(x), float(y)
        except ValueError:
            return False
        if abs(fx - fy) > tol * max(abs(fx), abs(fy)) + kAbsTol:
            return False
    return True


def split_output(text):
    lines = text.split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    headers = [l for l in lines if l.startswith("#")]
    data = [l for l in lines if not l.startswith("#")]
    return headers, data


def check_command(shown_lines, stdout, rel_tol=kRelTol):
    """Returns a list of problems (empty if the shown output matches to rel_tol)."""
    problems = []
    headers, data = split_output(stdout)
    columns = [h for h in headers if h.startswith("# columns:")]
    for line in shown_lines:
        if line.strip() == TRUNCATION:
            break
        if line.startswith("# columns:") and (not columns or not tokens_match(line, columns[0])):
            problems.append("columns line differs: shown %r, actual %r"
                            % (line, columns[0] if columns else None))
    shown_data = shown_data_lines(shown_lines)
    if len(shown_data) > len(data):
        problems.append("shows %d data lines, the command prints %d" % (len(shown_data), len(data)))
    names = columns[0].split()[2:] if columns else []
    for k, (s, a) in enumerate(zip(shown_data, data)):
        if not tokens_match(s, a, rel_tol, names):
            problems.append("data line %d differs:\n    shown:  %s\n    actual: %s" % (k + 1, s, a))
    return problems


def shown_data_lines(shown_lines):
    """The shown data lines: non-header lines before `...`, without trailing blank lines."""
    data = []
    for line in shown_lines:
        if line.strip() == TRUNCATION:
            break
        if not line.startswith("#"):
            data.append(line)
    while data and not data[-1].strip():
        data.pop()
    return data


def updated_output(shown_lines, stdout):
    headers, data = split_output(stdout)
    full_header = any(l.startswith("#") and not l.startswith("# columns:") for l in shown_lines)
    n = len(shown_data_lines(shown_lines))
    out = headers if full_header else [h for h in headers if h.startswith("# columns:")]
    out = out + data[:n]
    if len(data) > n:
        out.append(TRUNCATION)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cli", required=True)
    parser.add_argument("--update", action="store_true")
    parser.add_argument("tutorial")
    args = parser.parse_args()
    cli = os.path.abspath(args.cli)

    with open(args.tutorial, encoding="utf-8") as f:
        lines = f.read().split("\n")
    commands = list(parse_blocks(lines))
    if not commands:
        print("FAIL: no `$ coatcontact` commands found in %s" % args.tutorial)
        return 1

    failures = 0
    replacements = []
    with tempfile.TemporaryDirectory() as workdir:
        # Commands run in a scratch folder (their --output files land there) that sees the
        # repository's data/ folder, so the tutorial can use the example data sets.
        repo_data = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(args.tutorial))), "data")
        if os.path.isdir(repo_data):
            os.symlink(repo_data, os.path.join(workdir, "data"))
        for index, command, out_idx in commands:
            shown = [lines[i] for i in out_idx]
            try:
                code, stdout, stderr = run(cli, command, workdir)
            except (ValueError, subprocess.TimeoutExpired) as e:
                print("FAIL  line %d: %s" % (index + 1, e))
                failures += 1
                continue
            if code != 0:
                print("FAIL  line %d: `%s` exited %d\n%s" % (index + 1, command, code, stderr))
                failures += 1
                continue
            if args.update:
                replacements.append((out_idx, updated_output(shown, stdout)))
                print("updated line %d: %s" % (index + 1, command))
                continue
            problems = check_command(shown, stdout,
                                     kRelTolZoneLocation if "--lambda" in command else kRelTol)
            if problems:
                failures += 1
                print("FAIL  line %d: %s" % (index + 1, command))
                for p in problems:
                    print("    " + p)
            else:
                print("ok    line %d: %s" % (index + 1, command))

    if args.update and not failures:
        # Replace from the end so earlier indices stay valid.
        for out_idx, new in sorted(replacements, key=lambda r: -(r[0][0] if r[0] else 0)):
            if out_idx:
                lines[out_idx[0]:out_idx[-1] + 1] = new
            else:
                raise SystemExit("a command without output lines cannot be updated in place; "
                                 "add a placeholder line after it")
        with open(args.tutorial, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
    print("%d command(s), %d failure(s)" % (len(commands), failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
