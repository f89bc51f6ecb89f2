#!/usr/bin/env bash
# Checks that docs/table1.md and docs/img/table1/{profile,bars}.svg are what
# docs/table1/results.json and models/table1.toml give: regenerates them into a temporary
# directory (the page with scripts/table1-report.py, the charts with
# `NETSPEC compare --merge docs/table1 --manifest models/table1.toml`) and compares byte for
# byte. Exit 1 naming each file that differs; 2 when no netspec binary is found.
#
#   scripts/table1-check.sh [NETSPEC]
#
# NETSPEC: the netspec binary (default: $NETSPEC, else the release build under
# $CARGO_TARGET_DIR or ~/.cache/netspec/target). Needs python3 (3.11+) and nothing else.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-${NETSPEC:-${CARGO_TARGET_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/netspec/target}/release/netspec}}
if [[ ! -x $bin ]]; then
  echo "table1-check: no netspec binary at $bin (give its path, or set NETSPEC)" >&2
  exit 2
fi
exec python3 scripts/table1-report.py --check --netspec "$bin"
