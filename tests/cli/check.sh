# Sourced by the command-line tests: `check DESCRIPTION COMMAND...` runs COMMAND, prints ok or
# FAILED with the description, and counts failures (exit with "$failures" at the end).
failures=0
check() {
  local what=$1; shift
  if "$@"; then echo "ok: $what"; else echo "FAILED: $what"; failures=$((failures + 1)); fi
}
