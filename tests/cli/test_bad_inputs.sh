#!/usr/bin/env bash
# Bad values for every option of every subcommand (issue 7, label cli): each row gives one
# option a bad value (text, NaN, inf, negative, zero, out of range, empty, missing) on top of
# a valid command line and expects exit 2, an error line on stderr that names the option
# (or, for paths, the path), nothing on stdout, no file written and no sanitizer or Fortran
# runtime report. Cases already in tests/kernel/test_kernel_cli.sh,
# tests/solver/test_reduced_cli.sh, tests/adhesive/cli_bad_input.sh and
# tests/fit/test_fit_cli.sh are not repeated here.
# Out-of-range rows of adhesive, pulloff and sphere (--eta 1e-300, --a-bar 1e300, --radius
# 1e300, --thickness 1e-300, --work 1e300) exit 2 with the solver's or model's range message
# ("a/t ... is not allowed", "Maugis length ... not allowed"), which does not name the option;
# they fail until cpp/cli/cmd_adhesive.cpp names it (reported, issue 7).
# Usage: test_bad_inputs.sh PATH/TO/coatcontact DATA_DIR
set -u
cli="$1"
data="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
rows=0

# A valid command line per subcommand, one --option=value per word (the row's option is
# replaced, dropped or appended). fit's first word is the DATA file.
declare -A base
base[kernel]="--film=1GPa,0.3 --substrate=10GPa,0.25 --q=0.1,1 --u=0.5,2"
base[reduced]="--film=1GPa,0.3 --substrate=10GPa,0.25 --a-over-t=0.5,2 --tol=1e-6"
base[adhesive]="--film=1GPa,0.3 --substrate=10GPa,0.25 --eta=1 --a-bar=0.5,1 --tol=1e-6"
base[pulloff]="--film=1GPa,0.3 --substrate=10GPa,0.25 --eta=1 --tol=1e-6"
base[sphere]="--radius=5um --thickness=1um --film=1GPa,0.3 --substrate=10GPa,0.25 --work=50mJ/m2 --points=20 --tol=1e-6"
base[fit]="$data/example_a_F.tsv --columns=a,F --radius=5mm --film=1MPa,0.49 --substrate=70GPa,0.22 --free=w --start=w=50mJ/m2 --thickness=50um --branch=both"

# Every valid base line must succeed, or the rows below would test nothing.
for cmd in kernel reduced adhesive pulloff sphere fit; do
  read -r -a args <<<"${base[$cmd]}"
  if ! timeout 120 "$cli" "$cmd" "${args[@]}" >"$work/out" 2>"$work/err"; then
    echo "FAIL: base line of '$cmd' does not run: $(head -c 300 "$work/err")"
    failures=$((failures + 1))
  fi
done

# check CMD OPTION VALUE EXPECT: VALUE is the bad value ('@empty' = empty, '@missing' = option
# left out); OPTION 'DATA' is fit's data file. EXPECT must appear in stderr ('-' = OPTION).
check() {
  local cmd="$1" option="$2" value="$3" expect="$4"
  [ "$value" = "@empty" ] && value=""
  [ "$expect" = "-" ] && expect="$option"
  local -a args=() words=()
  read -r -a words <<<"${base[$cmd]}"
  local found=0 first=1 w
  for w in "${words[@]}"; do
    if [ "$option" = "DATA" ] && [ $first -eq 1 ] && [ "$cmd" = fit ]; then
      found=1
      [ "$value" != "@missing" ] && args+=("$value")
    elif [ "${w%%=*}" = "$option" ]; then
      found=1
      [ "$value" != "@missing" ] && args+=("$option=$value")
    else
      args+=("$w")
    fi
    first=0
  done
  [ $found -eq 0 ] && args+=("$option=$value")
  rows=$((rows + 1))
  timeout 120 "$cli" "$cmd" "${args[@]}" >"$work/out" 2>"$work/err"
  local rc=$?
  local why=""
  if [ $rc -ne 2 ]; then
    why="exit $rc, expected 2"
  elif ! grep -q -F -- "$expect" "$work/err"; then
    why="stderr does not name '$expect'"
  elif ! grep -q "^coatcontact $cmd: error: " "$work/err"; then
    why="stderr has no 'coatcontact $cmd: error:' line"
  elif grep -q -E "Sanitizer|runtime error|Fortran runtime" "$work/err"; then
    why="sanitizer or runtime report on stderr"
  elif [ -s "$work/out" ]; then
    why="something was written to stdout"
  elif [ -n "$(ls -A "$work/files")" ]; then
    why="a file was left in the output folder: $(ls -A "$work/files")"
  fi
  if [ -n "$why" ]; then
    echo "FAIL: coatcontact $cmd ${args[*]}"
    echo "      $why; stderr: $(head -c 400 "$work/err")"
    failures=$((failures + 1))
  else
    printf 'ok   %-9s %-12s %-22s -> %s\n' "$cmd" "$option" "'$value'" "$(head -n 1 "$work/err" | cut -c1-110)"
  fi
  rm -rf "$work/files"
  mkdir -p "$work/files"
}
mkdir -p "$work/files"
missing_dir="$work/files/no-such-folder/out.tsv"
# Issue 17: special targets live in their own folder (not $work/files, which must stay empty):
# a FIFO, a dangling symlink and (as root) a character device made here with mknod; never the
# system's /dev entries. (Same-file cases: test_regressions.sh fit_output_overwrites_data.)
special="$work/special"
mkdir -p "$special"
mkfifo "$special/fifo"
ln -s "$special/missing" "$special/dangling"
have_device=0
if [ "$(id -u)" -eq 0 ] && mknod -m 666 "$special/null" c 1 3 2>/dev/null; then have_device=1; fi

trim() {
  local s="$1"
  s="${s#"${s%%[![:space:]]*}"}"
  printf '%s' "${s%"${s##*[![:space:]]}"}"
}

# The table: command | option | bad value | text the message must contain ('-' = the option).
while IFS='|' read -r cmd option value expect; do
  cmd="$(trim "$cmd")"
  [ -z "$cmd" ] && continue
  case "$cmd" in \#*) continue ;; esac
  option="$(trim "$option")"
  value="$(trim "$value")"
  expect="$(trim "$expect")"
  case "$value" in @device*) [ $have_device -eq 1 ] || { echo "skip $cmd $option $value (mknod needs root)"; continue; } ;; esac
  value="${value//@device/$special/null}"
  value="${value//@fifo/$special/fifo}"
  value="${value//@dangling/$special/dangling}"
  value="${value//@nodir/$missing_dir}"
  value="${value//@folder/$work}"
  expect="${expect//@nodir/$missing_dir}"
  expect="${expect//@folder/$work}"
  check "$cmd" "$option" "$value" "$expect"
done <<'TABLE'
# ---- kernel (test_kernel_cli.sh has: film -1 and nu 0.6, substrate 0 and nu 0.6, --q 1,,2
#      and -1, --u 1:0.5:x, missing --film, --output into a missing folder)
kernel   | --film      | abc            | -
kernel   | --film      | nan,0.3        | -
kernel   | --film      | inf,0.3        | -
kernel   | --film      | 0,0.3          | -
kernel   | --film      | 1GPa,nan       | -
kernel   | --film      | 1GPa,-1        | -
kernel   | --film      | 1GPa           | -
kernel   | --film      | @empty         | -
kernel   | --substrate | soft           | -
kernel   | --substrate | nan,0.3        | -
kernel   | --substrate | inf,0.3        | -
kernel   | --substrate | -10GPa,0.3     | -
kernel   | --substrate | 10GPa,-1.5     | -
kernel   | --substrate | 10GPa,inf      | -
kernel   | --substrate | @empty         | -
kernel   | --substrate | @missing       | -
kernel   | --q         | abc            | -
kernel   | --q         | nan            | -
kernel   | --q         | inf            | -
kernel   | --q         | 1e400          | -
kernel   | --q         | 1:0.1:3        | -
kernel   | --q         | 0:1:3          | -
kernel   | --q         | 1:2:0          | -
kernel   | --q         | @empty         | -
kernel   | --u         | abc            | -
kernel   | --u         | nan            | -
kernel   | --u         | -inf           | -
kernel   | --u         | 1:2:2000000    | -
kernel   | --u         | @empty         | -
kernel   | --output    | @empty         | -
kernel   | --output    | @folder        | @folder
kernel   | --bogus     | 1              | -
# ---- issue 17: targets that are not regular files, or are an input / another output
kernel   | --output    | @device        | is a character device
kernel   | --output    | @fifo          | is a FIFO
kernel   | --output    | @dangling      | symbolic link
reduced  | --output    | @device        | not a regular file
reduced  | --output    | @fifo          | not a regular file
adhesive | --output    | @device        | -
adhesive | --output    | @fifo          | -
pulloff  | --output    | @device        | -
pulloff  | --output    | @fifo          | -
sphere   | --output    | @device        | -
sphere   | --output    | @fifo          | -
sphere   | --output    | @dangling      | -
sphere   | --contact-radius | 1e-320    | -
sphere   | --contact-radius | 1e300     | -
fit      | --output    | @device        | -
fit      | --output    | @fifo          | -
fit      | --curve     | @device        | -
fit      | --curve     | @fifo          | -
fit      | --curve     | @dangling      | -
kernel   | --u         | 1e-320         | -
kernel   | --q         | 1e-310         | -
kernel   | --film      | 1e308,0.25     | -
kernel   | --substrate | 1e-308,0.25    | -
reduced  | --a-over-t  | 1e-320         | -
reduced  | --tol       | 1e-320         | -
adhesive | --eta       | 1e-320         | -
sphere   | --radius    | 1e-320         | -
sphere   | --work      | 1e-320         | -
fit      | --radius    | 1e-320         | -
fit      | --thickness | 1e-320         | -
fit      | --start     | w=1e-320       | --start w
fit      | --start     | w=1e308        | --start w
fit      | --work      | 1e-320         | -
# ---- reduced (test_reduced_cli.sh has: --a-over-t -1, --tol 0.5, missing --substrate)
reduced  | --film      | abc            | -
reduced  | --film      | nan,0.3        | -
reduced  | --film      | inf,0.3        | -
reduced  | --film      | 0,0.3          | -
reduced  | --film      | -1GPa,0.3      | -
reduced  | --film      | 1GPa,0.51      | -
reduced  | --film      | 1GPa,nan       | -
reduced  | --film      | @empty         | -
reduced  | --film      | @missing       | -
reduced  | --substrate | rigidd         | -
reduced  | --substrate | nan,0.3        | -
reduced  | --substrate | inf,0.3        | -
reduced  | --substrate | 0,0.3          | -
reduced  | --substrate | -10GPa,0.3     | -
reduced  | --substrate | 10GPa,0.7      | -
reduced  | --substrate | @empty         | -
reduced  | --a-over-t  | abc            | -
reduced  | --a-over-t  | nan            | -
reduced  | --a-over-t  | inf            | -
reduced  | --a-over-t  | 0              | -
reduced  | --a-over-t  | 1e9            | -
reduced  | --a-over-t  | 1,,2           | -
reduced  | --a-over-t  | 2:1:5          | -
reduced  | --a-over-t  | @empty         | -
reduced  | --a-over-t  | @missing       | -
reduced  | --tol       | abc            | -
reduced  | --tol       | nan            | -
reduced  | --tol       | inf            | -
reduced  | --tol       | 0              | -
reduced  | --tol       | -1e-8          | -
reduced  | --tol       | 1e-14          | -
reduced  | --tol       | @empty         | -
reduced  | --output    | @empty         | -
reduced  | --output    | @nodir         | @nodir
reduced  | --output    | @folder        | @folder
reduced  | --bogus     | 1              | -
# ---- adhesive and pulloff (cli_bad_input.sh has: film abc / nu 0.7 / -1e9 / missing,
#      substrate soft / 0, eta empty item / 0 / -1 / abc / missing / '--eta=', tol 0 / 1 / x,
#      --output into a missing folder, --bogus; a-bar 0,1 / -0.5 / 1:0.1:5 / nan)
adhesive | --film      | nan,0.3        | -
adhesive | --film      | inf,0.3        | -
adhesive | --film      | 0,0.3          | -
adhesive | --film      | 1GPa,nan       | -
adhesive | --film      | @empty         | -
adhesive | --substrate | nan,0.3        | -
adhesive | --substrate | inf,0.3        | -
adhesive | --substrate | -10GPa,0.3     | -
adhesive | --substrate | 10GPa,-1       | -
adhesive | --substrate | @empty         | -
adhesive | --substrate | @missing       | -
adhesive | --eta       | nan            | -
adhesive | --eta       | inf            | -
adhesive | --eta       | 1e400          | -
adhesive | --eta       | 1e-300         | -
adhesive | --a-bar     | abc            | -
adhesive | --a-bar     | inf            | -
adhesive | --a-bar     | 1e300          | -
adhesive | --a-bar     | @empty         | -
adhesive | --tol       | nan            | -
adhesive | --tol       | inf            | -
adhesive | --tol       | -1e-8          | -
adhesive | --tol       | @empty         | -
adhesive | --output    | @empty         | -
adhesive | --output    | @folder        | @folder
pulloff  | --film      | nan,0.3        | -
pulloff  | --film      | inf,0.3        | -
pulloff  | --film      | 0,0.3          | -
pulloff  | --film      | 1GPa,nan       | -
pulloff  | --film      | @empty         | -
pulloff  | --substrate | nan,0.3        | -
pulloff  | --substrate | inf,0.3        | -
pulloff  | --substrate | -10GPa,0.3     | -
pulloff  | --substrate | 10GPa,-1       | -
pulloff  | --substrate | @empty         | -
pulloff  | --substrate | @missing       | -
pulloff  | --eta       | nan            | -
pulloff  | --eta       | inf            | -
pulloff  | --eta       | 1e400          | -
pulloff  | --eta       | 1e-300         | -
pulloff  | --tol       | nan            | -
pulloff  | --tol       | inf            | -
pulloff  | --tol       | -1e-8          | -
pulloff  | --tol       | @empty         | -
pulloff  | --output    | @empty         | -
pulloff  | --output    | @folder        | @folder
# ---- sphere (cli_bad_input.sh has: radius 0 / -5um / 5parsec / missing, thickness 0 / -1nm,
#      work 0 / -0.05 / 5GPa / missing, film without nu, substrate rigidd, points 1 / 2.5 /
#      many, tol 1e-20, --output into a missing folder)
sphere   | --radius    | abc            | -
sphere   | --radius    | nan            | -
sphere   | --radius    | inf            | -
sphere   | --radius    | 1e300          | -
sphere   | --radius    | @empty         | -
sphere   | --thickness | abc            | -
sphere   | --thickness | nan            | -
sphere   | --thickness | inf            | -
sphere   | --thickness | 1e-300         | -
sphere   | --thickness | @empty         | -
sphere   | --thickness | @missing       | -
sphere   | --work      | abc            | -
sphere   | --work      | nan            | -
sphere   | --work      | inf            | -
sphere   | --work      | 1e300          | -
sphere   | --work      | @empty         | -
sphere   | --film      | abc            | -
sphere   | --film      | nan,0.3        | -
sphere   | --film      | 0,0.3          | -
sphere   | --film      | -1GPa,0.3      | -
sphere   | --film      | 1GPa,0.6       | -
sphere   | --film      | @empty         | -
sphere   | --film      | @missing       | -
sphere   | --substrate | nan,0.3        | -
sphere   | --substrate | 0,0.3          | -
sphere   | --substrate | 10GPa,0.7      | -
sphere   | --substrate | @empty         | -
sphere   | --substrate | @missing       | -
sphere   | --points    | 0              | -
sphere   | --points    | -3             | -
sphere   | --points    | nan            | -
sphere   | --points    | inf            | -
sphere   | --points    | 1e7            | -
sphere   | --points    | @empty         | -
sphere   | --tol       | abc            | -
sphere   | --tol       | nan            | -
sphere   | --tol       | 0              | -
sphere   | --tol       | 0.5            | -
sphere   | --tol       | @empty         | -
sphere   | --output    | @empty         | -
sphere   | --output    | @folder        | @folder
sphere   | --bogus     | 1              | -
# ---- fit (test_fit_cli.sh has: malformed and negative data, too few points, fixed t without
#      --thickness, --free w,nu, --columns x,y, a missing data file, a unit of the wrong kind)
fit      | DATA        | @empty         | cannot read data file
fit      | DATA        | @folder        | @folder
fit      | DATA        | @missing       | data file
fit      | --columns   | a              | -
fit      | --columns   | a,F,delta      | -
fit      | --columns   | @empty         | -
fit      | --columns   | @missing       | -
fit      | --radius    | abc            | -
fit      | --radius    | nan            | -
fit      | --radius    | inf            | -
fit      | --radius    | 0              | -
fit      | --radius    | -5mm           | -
fit      | --radius    | 5parsec        | -
fit      | --radius    | @empty         | -
fit      | --radius    | @missing       | -
fit      | --film      | abc            | -
fit      | --film      | nan,0.49       | -
fit      | --film      | inf,0.49       | -
fit      | --film      | 0,0.49         | -
fit      | --film      | -1MPa,0.49     | -
fit      | --film      | 1MPa,0.6       | -
fit      | --film      | 1MPa,nan       | -
fit      | --film      | @empty         | -
fit      | --film      | @missing       | -
fit      | --substrate | hard           | -
fit      | --substrate | nan,0.22       | -
fit      | --substrate | inf,0.22       | -
fit      | --substrate | 0,0.22         | -
fit      | --substrate | 70GPa,-1       | -
fit      | --substrate | 70GPa          | -
fit      | --substrate | @empty         | -
fit      | --substrate | @missing       | -
fit      | --free      | @empty         | -
fit      | --free      | w,w            | -
fit      | --free      | w,             | -
fit      | --free      | 1              | -
fit      | --start     | abc            | -
fit      | --start     | w=abc          | -
fit      | --start     | w=nan          | -
fit      | --start     | w=inf          | -
fit      | --start     | w=0            | -
fit      | --start     | w=-40mJ/m2     | -
fit      | --start     | w=5um          | -
fit      | --start     | w=1,w=2        | -
fit      | --start     | t=40um         | -
fit      | --start     | nu=0.3         | -
fit      | --start     | @empty         | -
fit      | --thickness | abc            | -
fit      | --thickness | nan            | -
fit      | --thickness | inf            | -
fit      | --thickness | 0              | -
fit      | --thickness | -50um          | -
fit      | --thickness | @empty         | -
fit      | --work      | abc            | -
fit      | --work      | nan            | -
fit      | --work      | inf            | -
fit      | --work      | 0              | -
fit      | --work      | -0.05          | -
fit      | --work      | @empty         | -
fit      | --branch    | up             | -
fit      | --branch    | @empty         | -
fit      | --output    | @empty         | -
fit      | --output    | @nodir         | @nodir
fit      | --output    | @folder        | @folder
fit      | --curve     | @empty         | -
fit      | --curve     | @nodir         | @nodir
fit      | --bogus     | 1              | -
TABLE

if [ $failures -ne 0 ]; then
  echo "test_bad_inputs: $failures of $rows row(s) failed"
  exit 1
fi
echo "test_bad_inputs: all $rows rows passed"
