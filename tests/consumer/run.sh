#!/bin/sh
# tests/consumer/run.sh - builds and runs the consumer projects against this repository, the four
# ways a project takes prefilter in. Called by tests/portability/run.sh (`make consumers`,
# `make portability`); prints one line per way: ok/FAIL/SKIP NAME detail.
#
# usage: sh tests/consumer/run.sh OUTDIR [REPO]     (REPO defaults to this repository)
#   consumer-make         make install PREFIX=OUTDIR/make-prefix; tests/portability/smoke.c built
#                         with only -I<prefix>/include (the installed prefilter.h) and run
#   consumer-pkgconfig    the same install; tests/consumer/pkgconfig (a Makefile project) takes its
#                         flags from pkg-config --cflags prefilter
#   consumer-cmake-find   cmake configure + cmake --install of REPO to OUTDIR/cmake-prefix;
#                         tests/consumer/find_package (C++) uses find_package(prefilter)
#   consumer-cmake-subdir tests/consumer/add_subdirectory (C) vendors REPO with add_subdirectory
# Consumers are copied to OUTDIR and built there: the source tree stays clean.
set -u
OUT=$1
REPO=${2:-$(cd "$(dirname "$0")/../.." && pwd)}
HERE=$REPO/tests/consumer
mkdir -p "$OUT" || exit 2
OUT=$(cd "$OUT" && pwd)

have() { command -v "$1" >/dev/null 2>&1; }
line() { printf '%s %s %s\n' "$1" "$2" "$3"; }
# last line of a log, for the report
tail1() { tail -n 1 "$1" 2>/dev/null; }

# ---- make install + plain include path
MP=$OUT/make-prefix
if make -C "$REPO" install PREFIX="$MP" > "$OUT/make-install.log" 2>&1; then
    if ${CC:-cc} -std=c99 -Wall -Wextra -Werror -I"$MP/include" "$REPO/tests/portability/smoke.c" \
            -o "$OUT/make-smoke" -lm >> "$OUT/make-install.log" 2>&1 &&
        "$OUT/make-smoke" >> "$OUT/make-install.log" 2>&1; then
        line ok consumer-make "make install PREFIX=...: $(ls "$MP/include" | wc -l | tr -d ' ') headers + prefilter.pc, uninstall removes them; smoke.c on the installed prefilter.h: $(tail1 "$OUT/make-install.log")"
    else
        line FAIL consumer-make "smoke.c against the installed headers (log: $OUT/make-install.log)"
    fi
    # uninstall must remove what install wrote
    make -C "$REPO" uninstall PREFIX="$MP" >> "$OUT/make-install.log" 2>&1
    left=$(find "$MP" -type f | wc -l | tr -d ' ')
    [ "$left" -eq 0 ] || line FAIL consumer-make-uninstall "$left files left in $MP after make uninstall"
    make -C "$REPO" install PREFIX="$MP" >> "$OUT/make-install.log" 2>&1
else
    line FAIL consumer-make "make install failed (log: $OUT/make-install.log)"
fi

# ---- pkg-config
if ! have pkg-config; then
    line FAIL consumer-pkgconfig "pkg-config not found (Debian package pkgconf)"
else
    rm -rf "$OUT/pkgconfig" && cp -r "$HERE/pkgconfig" "$OUT/pkgconfig"
    if PKG_CONFIG_PATH="$MP/share/pkgconfig" make -C "$OUT/pkgconfig" > "$OUT/pkgconfig.log" 2>&1 &&
        "$OUT/pkgconfig/consumer" >> "$OUT/pkgconfig.log" 2>&1; then
        line ok consumer-pkgconfig "cflags '$(PKG_CONFIG_PATH="$MP/share/pkgconfig" pkg-config --cflags prefilter | sed 's/ *$//')', version $(PKG_CONFIG_PATH="$MP/share/pkgconfig" pkg-config --modversion prefilter); $(tail1 "$OUT/pkgconfig.log")"
    else
        line FAIL consumer-pkgconfig "log: $OUT/pkgconfig.log"
    fi
fi

# ---- CMake
if ! have cmake; then
    line FAIL consumer-cmake-find "cmake not found (Debian package cmake)"
    line FAIL consumer-cmake-subdir "cmake not found (Debian package cmake)"
    exit 0
fi
CP=$OUT/cmake-prefix
log=$OUT/cmake-find.log
if cmake -S "$REPO" -B "$OUT/cmake-repo" -DCMAKE_INSTALL_PREFIX="$CP" > "$log" 2>&1 &&
    cmake --install "$OUT/cmake-repo" >> "$log" 2>&1 &&
    cmake -S "$HERE/find_package" -B "$OUT/find_package" -DCMAKE_PREFIX_PATH="$CP" >> "$log" 2>&1 &&
    cmake --build "$OUT/find_package" >> "$log" 2>&1 &&
    "$OUT/find_package/consumer" >> "$log" 2>&1; then
    pc=""; [ -f "$CP/share/pkgconfig/prefilter.pc" ] && pc=" + prefilter.pc"
    line ok consumer-cmake-find "cmake --install (prefilterConfig.cmake$pc); find_package(prefilter 0.1), C++: $(tail1 "$log")"
else
    line FAIL consumer-cmake-find "log: $log"
fi
log=$OUT/cmake-subdir.log
if cmake -S "$HERE/add_subdirectory" -B "$OUT/add_subdirectory" -DPREFILTER_SOURCE_DIR="$REPO" > "$log" 2>&1 &&
    cmake --build "$OUT/add_subdirectory" >> "$log" 2>&1 &&
    "$OUT/add_subdirectory/consumer" >> "$log" 2>&1; then
    line ok consumer-cmake-subdir "add_subdirectory(prefilter), C, prefilter.h: $(tail1 "$log")"
else
    line FAIL consumer-cmake-subdir "log: $log"
fi
