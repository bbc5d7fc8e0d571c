#!/usr/bin/env bash
# docs_drift.sh - what README.md and the site's pages (docs/) say of the
# repository stays true: every document they name is in the repository (the
# README once cited an EPUCK.md that was not); only make run's own scenario
# says it is make run's default (random_walk.yaml once did); and the two
# random walks are described each with its own tumble chance and rate, as the
# simulator's --help gives their defaults (they were once one "random walk"
# with the forager's rate beside the controller's default).  Links between
# pages are checked by `make docs` (mkdocs build --strict), the footprint
# table by make firmware-check, the pages' runnable commands by
# tests/docs/runnable.py.  Usage: docs_drift.sh SWARMSIM.  (Under a second.)
set -u
cd "$(dirname "$0")/../.."
sim=${1:-build/swarmsim}
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $1"; }

# The pages: README.md and the site's, less the design notes (a record of
# their time, not a description of the present).
pages=(README.md $(find docs -name '*.md' -not -path 'docs/notes/*' | sort))

# Documents: *.md paths named in a page's text (not the outputs it describes,
# not the links between pages, which the docs build checks).  A path is the
# repository's (docs/x.md, lcm_types/README.md) or, in a page, its own folder's.
for page in "${pages[@]}"; do
    for doc in $(sed -E 's/\]\([^)]*\)/]/g' "$page" | grep -oE '[A-Za-z0-9_./-]+\.md\b' \
                 | grep -vE '^(results|footprint|footprint_readme|cpu)\.md$|^(build|out)/' | sort -u); do
        if [ -f "$doc" ] || [ -f "$(dirname "$page")/$doc" ]; then ok
        else bad "$page names $doc, which is not in the repository"; fi
    done
done

# A compiler message a page quotes points at the line it names: the
# descriptor check's bit-field in firmware/common/param.h (the message once
# named a line that had moved).
want=$(grep -n 'int descriptor_type_differs_from_the_field_type' firmware/common/param.h | cut -d: -f1)
for at in $(grep -ohE 'firmware/common/param\.h:[0-9]+:' "${pages[@]}" | sort -u); do
    line=${at#*param.h:}; line=${line%:}
    if [ "$line" = "$want" ]; then ok; else bad "a page quotes $at but the bit-field is on line $want of firmware/common/param.h"; fi
done

# make run's default scenario.
default=$(sed -n 's/^RUN_SCENARIO ?= //p' Makefile)
if [ -f "$default" ]; then ok; else bad "Makefile's RUN_SCENARIO '$default' does not exist"; fi
for f in $(grep -liE 'default scenario of .?make run|make run.?.s default' sim_host/scenarios/*.yaml); do
    if [ "$f" = "$default" ]; then ok; else bad "$f says it is make run's default scenario; the Makefile runs $default"; fi
done

# Each walk: its controller's turn_chance default from --help, and the README's
# line for it with that chance and its mean time between tumbles
# (65536 / chance steps of 100 ms).
default_turn_chance() {   # the turn_chance default under "when controller is $1"
    "$sim" --help | awk -v c="controller is $1 " '
        /params when controller is|params: none when/ { on = index($0, c) > 0 }
        on && $1 == "robots[].params.turn_chance" { print $3; exit }'
}
check_walk() {   # controller, the README's words that start its line
    local chance seconds line
    chance=$(default_turn_chance "$1")
    if [ -z "$chance" ]; then bad "no turn_chance default for $1 in $sim --help"; return; fi
    seconds=$(awk -v c="$chance" 'BEGIN { printf "%d", 65536 / c * 0.1 + 0.5 }')
    line=$(grep -hF -- "- $2" "${pages[@]}")
    if [ -z "$line" ]; then bad "no page has a line '- $2' for $1's walk"; return; fi
    if grep -qF "\`turn_chance\` $chance/65536" <<<"$line" && grep -qF "a tumble every $seconds s" <<<"$line"; then ok
    else bad "the line for $1's walk should give \`turn_chance\` $chance/65536 and a tumble every $seconds s: $line"; fi
}
check_walk random_walk "the \`random_walk\` controller"
check_walk forager "the forager's search walk"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
