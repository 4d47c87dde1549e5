#!/usr/bin/env bash
# Prints the --help of every `pastemix` command and subcommand, recursively, with the binary's path blanked,
# so that two builds' CLIs can be compared with diff (a refactor of the registrations must not change them):
#   diff <(scripts/cli_help_dump.sh OLD/pastemix) <(scripts/cli_help_dump.sh build/pastemix)
set -euo pipefail
BIN="${1:?usage: scripts/cli_help_dump.sh PATH/TO/pastemix}"
walk() {
  local out subs
  out="$("$BIN" "$@" --help 2>&1 | sed "s#$BIN#PASTEMIX#g")"
  echo "=== $*"
  echo "$out"
  subs=$(echo "$out" | awk '/^Subcommands:/{f=1;next} f&&/^  [a-z]/{print $1} f&&/^$/{f=0}')
  for s in $subs; do walk "$@" "$s"; done
}
walk
