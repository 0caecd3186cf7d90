#!/usr/bin/env bash
# Regression (issue 40, item 1; label cli): `--cache DIR` / COATCONTACT_CACHE=DIR deleted every
# file or folder of DIR named with 16 hex digits, the user's included, also through a linked
# DIR. The cache may only remove what it provably wrote (docs/solver.md, "Solve cache"):
#  - a folder that is not its own (non-empty without coatcontact's CACHEDIR.TAG), a regular
#    file, /dev/null or a dangling link is refused: exit 2 naming the option or variable, the
#    value and what is allowed, nothing on stdout, nothing in it changed;
#  - an absent or empty folder is made the cache's (CACHEDIR.TAG written);
#  - inside its own folder it removes only files whose name and first line are its own (another
#    build's entries, a corrupt entry of its own), never a user's file with a look-alike name
#    or a look-alike folder, and never follows a link.
# usage: test_cache_never_deletes_user_files.sh <coatcontact binary>
set -uo pipefail
cli=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# shellcheck disable=SC2054  # commas inside an option value
command=(reduced --film 0.1,0.25 --substrate 1,0.25 --a-over-t 0.1:10:3)
env -u COATCONTACT_CACHE "$cli" "${command[@]}" > "$tmp/reference" || { echo "FAIL: reference run"; exit 1; }

# A folder of the user's whose names look like the cache's: snapshot of every path and content.
make_user_folder() {
  mkdir -p "$1/fedcba9876543210/solve-0123456789abcdef" "$1/notes"
  echo "thesis draft" > "$1/0123456789abcdef"
  echo "results" > "$1/fedcba9876543210/data.tsv"
  echo "coatcontact solve cache 1 (a user's note)" > "$1/fedcba9876543210/solve-0123456789abcdef/1a2b-12-0.bin"
  echo "keep" > "$1/notes/todo.txt"
}
snapshot() { (cd "$1" && find . -print0 | sort -z | xargs -0 -I{} sh -c 'printf "%s " "{}"; [ -f "{}" ] && md5sum < "{}" || echo dir'); }

# refused <label> <text the message must hold> <run...>: exit 2, the message, nothing on stdout.
refused() {
  local label=$1 text=$2
  shift 2
  "$@" > "$tmp/out" 2> "$tmp/err"
  local code=$?
  [ "$code" -eq 2 ] || fail "$label: exit $code, expected 2 ($(head -c 300 "$tmp/err"))"
  grep -q -F -- "$text" "$tmp/err" || fail "$label: message does not name '$text': $(head -c 300 "$tmp/err")"
  grep -q -F -- "allowed" "$tmp/err" || fail "$label: message does not say what is allowed: $(head -c 300 "$tmp/err")"
  [ ! -s "$tmp/out" ] || fail "$label: wrote to stdout"
}

echo "== a folder of the user's: refused, nothing deleted (--cache, COATCONTACT_CACHE, a link to it)"
user="$tmp/user"
make_user_folder "$user"
before=$(snapshot "$user")
refused "--cache USERDIR" "--cache '$user'" env -u COATCONTACT_CACHE "$cli" --cache "$user" "${command[@]}"
refused "COATCONTACT_CACHE=USERDIR" "COATCONTACT_CACHE '$user'" env COATCONTACT_CACHE="$user" "$cli" "${command[@]}"
ln -s "$user" "$tmp/link"
refused "--cache LINK" "--cache '$tmp/link'" env -u COATCONTACT_CACHE "$cli" --cache "$tmp/link" "${command[@]}"
refused "COATCONTACT_CACHE=LINK/" "COATCONTACT_CACHE" env COATCONTACT_CACHE="$tmp/link/" "$cli" "${command[@]}"
[ "$before" = "$(snapshot "$user")" ] || fail "the user's folder changed"

echo "== a regular file, /dev/null, a dangling link: refused"
echo "not a folder" > "$tmp/file"
refused "--cache FILE" "is a file" env -u COATCONTACT_CACHE "$cli" --cache "$tmp/file" "${command[@]}"
[ "$(cat "$tmp/file")" = "not a folder" ] || fail "the regular file changed"
refused "--cache /dev/null" "not a folder" env -u COATCONTACT_CACHE "$cli" --cache /dev/null "${command[@]}"
refused "COATCONTACT_CACHE=/dev/null" "COATCONTACT_CACHE '/dev/null'" env COATCONTACT_CACHE=/dev/null "$cli" "${command[@]}"
ln -s "$tmp/nowhere" "$tmp/dangling"
refused "--cache DANGLING" "symbolic link to nothing" env -u COATCONTACT_CACHE "$cli" --cache "$tmp/dangling" "${command[@]}"
[ ! -e "$tmp/nowhere" ] || fail "the dangling link's target was created"
# Commands that read no cache are not affected by a refused one: help and version still work.
env COATCONTACT_CACHE="$user" "$cli" --version > /dev/null || fail "--version with a refused COATCONTACT_CACHE failed"

echo "== an empty folder and an absent one: made the cache's (CACHEDIR.TAG), same outputs"
for dir in "$tmp/empty" "$tmp/absent/cache"; do
  [ "$dir" = "$tmp/empty" ] && mkdir "$dir"
  env -u COATCONTACT_CACHE "$cli" --cache "$dir" "${command[@]}" > "$tmp/out" || fail "--cache $dir: exit $?"
  cmp -s "$tmp/out" "$tmp/reference" || fail "--cache $dir: output differs from no cache"
  head -n 1 "$dir/CACHEDIR.TAG" 2>/dev/null | grep -q '^Signature: 8a477f597d28d172789f06886806bc55$' ||
    fail "$dir: no cache directory tag written"
  [ -n "$(find "$dir" -name '*.bin')" ] || fail "$dir: no entry written"
done

echo "== a folder holding only what the cache writes, untagged (an earlier version's): adopted and read"
cp -r "$tmp/empty" "$tmp/legacy"
rm "$tmp/legacy/CACHEDIR.TAG"
before=$(find "$tmp/legacy" -name '*.bin' | sort)
env -u COATCONTACT_CACHE "$cli" --cache "$tmp/legacy" "${command[@]}" > "$tmp/out" || fail "--cache LEGACY: exit $?"
cmp -s "$tmp/out" "$tmp/reference" || fail "--cache LEGACY: output differs from no cache"
[ -f "$tmp/legacy/CACHEDIR.TAG" ] || fail "--cache LEGACY: not adopted (no tag)"
[ "$before" = "$(find "$tmp/legacy" -name '*.bin' | sort)" ] || fail "--cache LEGACY: its entries were not read (solved again)"

echo "== inside its own folder: only its own files removed"
cache="$tmp/empty"
build=$(cd "$cache" && find . -mindepth 1 -maxdepth 1 -type d -name '????????????????' | head -n 1)
build=${build#./}
[ -n "$build" ] || fail "no build folder in $cache"
own_entry=$(find "$cache/$build" -path '*/solve-*' -name '*.bin' | head -n 1)
# Another build's entries (its own format: removed), the user's look-alikes (kept), a link to
# the user's folder under a build folder's name (not followed).
mkdir -p "$cache/0000000000000000/solve-00000000000000aa"
cp "$own_entry" "$cache/0000000000000000/solve-00000000000000aa/1-2-3.bin"
make_user_folder "$cache"
mkdir -p "$tmp/target/solve-00000000000000bb"
cp "$own_entry" "$tmp/target/solve-00000000000000bb/4-5-6.bin"
ln -s "$tmp/target" "$cache/aaaaaaaaaaaaaaaa"
key_folder=$(dirname "$own_entry")
kept=$(snapshot "$cache" | grep -v -e "^./$build" -e '^./0000000000000000' -e '^./CACHEDIR.TAG'; echo "link $(readlink "$cache/aaaaaaaaaaaaaaaa")")
target_before=$(snapshot "$tmp/target")
rm -rf "${cache:?}/$build"  # the next writer is the first of "a new build": it clears the others
env -u COATCONTACT_CACHE "$cli" --cache "$cache" "${command[@]}" > "$tmp/out" || fail "run in its own folder: exit $?"
cmp -s "$tmp/out" "$tmp/reference" || fail "run in its own folder: output differs from no cache"
[ ! -e "$cache/0000000000000000" ] || fail "another build's entries were not removed"
now=$(snapshot "$cache" | grep -v -e "^./$build" -e '^./0000000000000000' -e '^./CACHEDIR.TAG'; echo "link $(readlink "$cache/aaaaaaaaaaaaaaaa")")
[ "$kept" = "$now" ] || fail "a file of the user's in the cache folder changed: $(diff <(echo "$kept") <(echo "$now") | head -n 5)"
[ "$target_before" = "$(snapshot "$tmp/target")" ] || fail "the cache worked behind a link"
# In its key folder: the user's files stay, a corrupt entry of its own (a byte changed in its
# key line or in its records) is removed and solved again.
echo "user text" > "$key_folder/notes.txt"
echo "user text with an entry's name" > "$key_folder/abc-1-1.bin"
victim=$(find "$key_folder" -name '*.bin' ! -name 'abc-1-1.bin' | head -n 1)
printf '\x01' | dd of="$victim" bs=1 seek=100 conv=notrunc status=none
env -u COATCONTACT_CACHE "$cli" --cache "$cache" "${command[@]}" > "$tmp/out" || fail "corrupt entry: exit $?"
cmp -s "$tmp/out" "$tmp/reference" || fail "corrupt entry: output differs from no cache"
[ ! -e "$victim" ] || fail "the corrupt entry of the cache's own was not removed"
[ "$(cat "$key_folder/notes.txt" 2>/dev/null)" = "user text" ] || fail "a user's file in a key folder was removed"
[ -e "$key_folder/abc-1-1.bin" ] || fail "a user's file named like an entry was removed with a corrupt one"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "the cache removed nothing of the user's"
