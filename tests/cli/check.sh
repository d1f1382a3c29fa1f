# Sourced by the command-line tests: `check DESCRIPTION COMMAND...` runs COMMAND, prints ok or
# FAILED with the description, and counts failures (exit with "$failures" at the end).
failures=0
check() {
  local what=$1; shift
  if "$@"; then echo "ok: $what"; else echo "FAILED: $what"; failures=$((failures + 1)); fi
}
# `interrupted_after SECONDS COMMAND...`: runs COMMAND in the background (with the caller's
# redirections), sends it SIGINT after SECONDS and returns its exit code.
interrupted_after() {
  local delay=$1; shift
  "$@" &
  local pid=$!
  sleep "$delay"
  kill -INT $pid
  wait $pid
}
# `wait_for_lines FILE N`: until FILE has N lines (a run in the background has got that far and
# installed its signal handlers), for at most 20 s.
wait_for_lines() {
  local file=$1 lines=$2
  for _ in $(seq 1 400); do
    [ "$(wc -l < "$file" 2>/dev/null || echo 0)" -ge "$lines" ] && return 0
    sleep 0.05
  done
}
