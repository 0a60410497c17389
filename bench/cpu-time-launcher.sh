#!/usr/bin/env bash
# A compiler launcher (CMAKE_CXX_COMPILER_LAUNCHER) that runs the compiler without ccache and
# appends its CPU seconds (user+sys) and source file to $TESSERA_CPU_LOG: how
# bench/cold-build-cpu.sh measures a cold build on a shared machine, where wall time says little.
source=""
previous=""
for arg in "$@"; do
  [ "$previous" = "-c" ] && source=$arg
  previous=$arg
done
times=$(mktemp)
/usr/bin/time -f "%U %S" -o "$times" "$@"
status=$?
awk -v source="$source" '{ printf "%.1f %s\n", $1 + $2, source }' "$times" >>"${TESSERA_CPU_LOG:?}"
rm -f "$times"
exit $status
