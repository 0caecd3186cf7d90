#!/usr/bin/env bash
# Install test: `cmake --install BUILD --prefix TMP`, then a C and a C++ consumer built against
# TMP once through find_package(coatcontact) (consumer/CMakeLists.txt) and once through
# pkg-config; each prints E_eq of film 0.1,0.25 on substrate 1,0.25 at a/t = 1, which must match
# `CLI reduced` (column E_eq) to 1e-12 relative. So must the installed program's. Every
# installed header must compile alone and all of them together, C headers as C99 and C++17.
# Usage: run_install_test.sh BUILD_DIR SOURCE_DIR CLI
# Tools from the environment (tests/install/CMakeLists.txt sets them): CMAKE, CC, CXX, PKG_CONFIG.
set -euo pipefail

if [ $# -ne 3 ]; then
  echo "usage: $0 BUILD_DIR SOURCE_DIR CLI" >&2
  exit 2
fi
build=$1
consumer=$2/tests/install/consumer
cli=$3
cmake=${CMAKE:-cmake}
cc=${CC:-cc}
cxx=${CXX:-c++}
pkg_config=${PKG_CONFIG:-pkg-config}

work=$(mktemp -d "${TMPDIR:-/tmp}/coatcontact-install.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
failures=0

fail() {
  echo "FAIL $*"
  failures=$((failures + 1))
}

# Runs "$@", showing its output only when it fails.
quiet() {
  local log=$work/step.log
  if ! "$@" > "$log" 2>&1; then
    cat "$log"
    echo "command failed: $*" >&2
    exit 1
  fi
}

# E_eq column of `coatcontact reduced` output (the header names the columns).
e_eq_of_table() {
  awk -F'\t' '/^# columns: / { sub(/^# columns: /, ""); for (i = 1; i <= NF; ++i) if ($i == "E_eq") col = i; next }
              !/^#/ && NF > 1 { print $col; exit }'
}

# check NAME VALUE: VALUE equals the CLI's E_eq to 1e-12 relative.
check() {
  if awk -v a="$2" -v b="$expected" 'BEGIN { d = a - b; if (d < 0) d = -d; s = b < 0 ? -b : b;
                                             exit !(a != "" && d <= 1e-12 * s) }'; then
    echo "ok   $1: E_eq = $2"
  else
    fail "$1: E_eq = '$2', expected $expected"
  fi
}

case_args=(reduced --film "0.1,0.25" --substrate "1,0.25" --a-over-t 1)
expected=$("$cli" "${case_args[@]}" | e_eq_of_table)
echo "CLI: E_eq = $expected"
[ -n "$expected" ] || { echo "FAIL no E_eq from $cli" >&2; exit 1; }

# --- install ---
quiet "$cmake" --install "$build" --prefix "$prefix"
pc_file=$(find "$prefix" -name coatcontact.pc -path '*/pkgconfig/*')
config_file=$(find "$prefix" -name coatcontactConfig.cmake)
[ -n "$pc_file" ] || fail "no coatcontact.pc under $prefix"
[ -n "$config_file" ] || fail "no coatcontactConfig.cmake under $prefix"
for f in bin/coatcontact include/coatcontact/coatcontact.h include/coatcontact/reduced.hpp \
         include/coatcontact/cc_kernel.h include/coatcontact/cc_status.h include/coatcontact/coatcontact_afm.h \
         share/coatcontact/gnuplot/style.gp; do
  [ -e "$prefix/$f" ] || fail "not installed: $f"
done
for f in include/coatcontact/cli_support.hpp include/coatcontact/data_file.hpp; do
  [ ! -e "$prefix/$f" ] || fail "CLI header installed: $f"
done
[ "$failures" -eq 0 ] || exit 1

# --- every installed header compiles alone and all together: C headers as C and as C++,
# C++ headers as C++17, warnings as errors ---
include_dir=$prefix/include
mapfile -t c_headers < <(cd "$include_dir" && find coatcontact -name '*.h' | sort)
mapfile -t cxx_headers < <(cd "$include_dir" && find coatcontact -name '*.hpp' | sort)
[ "${#c_headers[@]}" -ge 2 ] || fail "fewer than two C headers installed: ${c_headers[*]}"
[ "${#cxx_headers[@]}" -ge 1 ] || fail "no C++ header installed"
# compile_header LANGUAGE COMPILER STD HEADER...: one translation unit including HEADER...
compile_header() {
  local language=$1 compiler=$2 std=$3 unit
  shift 3
  unit=$work/unit.$([ "$language" = c ] && echo c || echo cpp)
  printf '#include <%s>\n' "$@" > "$unit"
  printf 'int main(void) { return 0; }\n' >> "$unit"
  if "$compiler" -std="$std" -Wall -Wextra -pedantic -Werror -fsyntax-only -I"$include_dir" \
       "$unit" > "$work/header.log" 2>&1; then
    return 0
  fi
  cat "$work/header.log"
  return 1
}
for h in "${c_headers[@]}"; do
  compile_header c "$cc" c99 "$h" || fail "C header does not compile alone as C: $h"
  compile_header cxx "$cxx" c++17 "$h" || fail "C header does not compile alone as C++: $h"
done
for h in "${cxx_headers[@]}"; do
  compile_header cxx "$cxx" c++17 "$h" || fail "C++ header does not compile alone: $h"
done
compile_header c "$cc" c99 "${c_headers[@]}" || fail "the C headers do not compile together as C"
compile_header cxx "$cxx" c++17 "${c_headers[@]}" "${cxx_headers[@]}" ||
  fail "the installed headers do not compile together as C++"
echo "ok   ${#c_headers[@]} C and ${#cxx_headers[@]} C++ headers compile alone and together"
[ "$failures" -eq 0 ] || exit 1
check "installed program" "$("$prefix/bin/coatcontact" "${case_args[@]}" | e_eq_of_table)"

# --- find_package(coatcontact) ---
quiet "$cmake" -S "$consumer" -B "$work/consumer-build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx"
found=$(sed -n 's/^coatcontact_DIR:PATH=//p' "$work/consumer-build/CMakeCache.txt")
[ "$found" = "$(dirname "$config_file")" ] || fail "find_package used '$found', not $prefix"
quiet "$cmake" --build "$work/consumer-build"
check "find_package, C" "$("$work/consumer-build/consumer_c")"
check "find_package, C++" "$("$work/consumer-build/consumer_cxx")"

# --- pkg-config ---
# Static libraries need their private dependencies too (--static), shared ones do not.
PKG_CONFIG_PATH=$(dirname "$pc_file")${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}
export PKG_CONFIG_PATH
libdir=$("$pkg_config" --variable=libdir coatcontact)
static=()
if ! compgen -G "$libdir/libcoatcontact.so*" > /dev/null && \
   ! compgen -G "$libdir/libcoatcontact*.dylib" > /dev/null; then
  static=(--static)
fi
read -r -a cflags <<< "$("$pkg_config" "${static[@]}" --cflags coatcontact)"
read -r -a libs <<< "$("$pkg_config" "${static[@]}" --libs coatcontact)"
echo "pkg-config ${static[*]}: ${cflags[*]} ${libs[*]}"
quiet "$cc" -o "$work/pc_consumer_c" "$consumer/consumer.c" "${cflags[@]}" "${libs[@]}" \
  -Wl,-rpath,"$libdir"
quiet "$cxx" -std=c++17 -o "$work/pc_consumer_cxx" "$consumer/consumer.cpp" "${cflags[@]}" \
  "${libs[@]}" -Wl,-rpath,"$libdir"
check "pkg-config, C" "$("$work/pc_consumer_c")"
check "pkg-config, C++" "$("$work/pc_consumer_cxx")"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all install checks passed"
