#!/usr/bin/env bash
# The command line as a command line: --version, --help on stdout, did-you-mean, required options,
# help wrapped to the width, the status line of long commands on a terminal only (run under a
# pseudo-terminal with `script`), and the exit code of a branch stopped short of its bound.
# Usage: terminal_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
row2="$src/cases/row2.toml"

"$bin" --version > "$work/version.out" 2> "$work/version.err"
check "--version exits 0" test $? -eq 0
check "--version prints the name and a version" grep -Eq '^sympathy [0-9]+\.[0-9]+\.[0-9]+$' "$work/version.out"

"$bin" --help > "$work/help.out" 2> "$work/help.err"
check "--help exits 0" test $? -eq 0
check "--help goes to stdout" grep -q 'continue' "$work/help.out"
check "--help writes nothing to stderr" test ! -s "$work/help.err"
"$bin" > /dev/null 2> "$work/none.err"
check "no command exits 2 with the usage on stderr" test $? -eq 2
check "... the usage on stderr" grep -q 'usage: sympathy COMMAND' "$work/none.err"

"$bin" contineu "$row2" 2> "$work/typo.err"
check "a mistyped command exits 2" test $? -eq 2
check "... and suggests the command" grep -q "did you mean 'continue'?" "$work/typo.err"
"$bin" continue "$row2" --start in-phase --param k --from 30 --to 31 --max-point 3 2> "$work/opt.err"
check "a mistyped option exits 2" test $? -eq 2
check "... and suggests the option" grep -q "did you mean '--max-points'?" "$work/opt.err"
"$bin" continue "$row2" --start in-phase --from 30 --to 31 2> "$work/required.err"
check "a missing required option exits 2" test $? -eq 2
check "... naming it" grep -q "missing --param P for 'sympathy continue'" "$work/required.err"

COLUMNS=120 "$bin" continue --help > "$work/wide.out"
check "required options are in the synopsis, without brackets" \
  grep -q 'usage: sympathy continue CASE --param P --from A --to B \[options\]' "$work/wide.out"
COLUMNS=60 "$bin" continue --help > "$work/narrow.out"
longest=$(awk '{ if (length($0) > n) n = length($0) } END { print n }' "$work/narrow.out")
check "help wrapped to COLUMNS=60 (longest line $longest)" test "$longest" -le 60
COLUMNS=60 "$bin" equilibria --help > "$work/generic.out"
check "help of --set names no metronome parameter" bash -c "! grep -q 'kappa' '$work/generic.out'"

# The status line: under a pseudo-terminal, rewritten in place (carriage return, erase to the end
# of the line); absent with --quiet, and absent when stderr is not a terminal.
branch=(continue "$row2" --start in-phase --param k --from 30 --to 34 --max-points 6)
script -qec "$(printf '%q ' "$bin" "${branch[@]}")" /dev/null > "$work/tty.out"
check "on a terminal the branch's place in its window is shown" grep -q '% of 30 to 34' "$work/tty.out"
check "... as a line rewritten in place" grep -q $'\r\033\[K' "$work/tty.out"
script -qec "$(printf '%q ' "$bin" "${branch[@]}" --quiet)" /dev/null > "$work/quiet.out"
check "--quiet shows no status line" bash -c "! grep -q '% of' '$work/quiet.out'"
"$bin" "${branch[@]}" > "$work/pipe.out" 2>&1
check "not on a terminal, no status line" bash -c "! grep -q $'\033' '$work/pipe.out'"
rm -rf "$work/sweep"
sweep=(sweep "$row2" --start in-phase --over k=30:40:3 --out "$work/sweep" --threads 1)
script -qec "$(printf '%q ' "$bin" "${sweep[@]}")" /dev/null > "$work/sweep.out"
check "a sweep shows its count on a terminal" grep -q 'sweep: 3 of 3 orbits' "$work/sweep.out"
check "... with the time left while it runs" grep -q 'sweep: 1 of 3 orbits, [0-9]* s, about' "$work/sweep.out"

study=(study "$src/cases/figures/fig08.toml" --out "$work/study")
script -qec "$(printf '%q ' "$bin" "${study[@]}")" /dev/null > "$work/study.out"
check "a study shows its branches done on a terminal" grep -q 'study: 2 of 2 branches' "$work/study.out"
check "... and where a running one is" grep -Eq 'study: [01] of 2 branches, [0-9]+ s[^;]*; [a-z-]+ k = ' "$work/study.out"

# A branch that ends short of its bound for a numerical reason (the Hopf normal form with a
# rotation that grows without bound as the cycle's radius nears 1, at mu = 1: the period goes to 0
# and the corrector fails there): exit code 7, with what it computed written.
cat > "$work/singular.toml" <<'TOML'
kind = "equations"
name = "singular"
description = "Hopf normal form whose rotation is infinitely fast at r = 1"

[states]
x = 0.5
y = 0.0

[parameters]
mu = 0.25

[intermediates]
r2 = "x^2 + y^2"

[equations]
x = "mu*x - y/(1 - r2) - x*r2"
y = "x/(1 - r2) + mu*y - y*r2"
TOML
"$bin" continue "$work/singular.toml" --param mu --from 0.2 --to 2 --quiet \
  --json "$work/singular.json" > "$work/singular.out"
code=$?
check "a branch stopped at the minimum step exits 7 (got $code)" test $code -eq 7
check "... and says why" grep -q 'stopped: step size below the minimum' "$work/singular.out"
check "... with its points written" grep -q '"points"' "$work/singular.json"

exit $failures
