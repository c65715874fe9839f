#!/usr/bin/env bash
# Keeps the libraries' includes to their one-way dependency graph (docs/architecture.md):
# a file may include only from its own library and the libraries listed for it here.
# Run by the test suite (test "Layering"); prints each offending include and fails.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
declare -A allowed=(
  [engine]="engine"
  [materials]="engine materials"
  [io/config]="io/config io/common"
  [io/common]="io/common"
  [io/terrain]="io/terrain io/config io/common engine"
  [io/output]="io/output io/common engine"
  [io/scene]="io/scene io/config io/common io/terrain io/output engine materials"
  [io/run]="io/run io/scene io/output io/common io/config engine"
  [hazard]="hazard io/scene io/output io/terrain io/common io/config engine"
  [python]="python io/run io/scene io/output io/terrain io/common io/config engine hazard tools"
)
bad=0
for lib in "${!allowed[@]}"; do
  while IFS= read -r line; do
    file="${line%%:*}"
    inc="$(sed -E 's/.*#include "([^"]+)".*/\1/' <<<"${line#*:}")"
    ok=0
    for a in ${allowed[$lib]}; do
      case "$inc" in "$a"/*) ok=1 ;; esac
    done
    if [[ $ok -eq 0 ]]; then
      echo "layering: $file includes \"$inc\" (library $lib may include only: ${allowed[$lib]})"
      bad=1
    fi
  done < <(cd "$root" && grep -rHn '#include "' "$lib" --include='*.h' --include='*.cpp' --include='*.in' | sed -E 's/^([^:]+):[0-9]+:/\1:/')
done
exit $bad
