#!/usr/bin/env bash
# floor_bench.sh - the floor benchmark (tools/bench/floor_bench.c) still
# measures what it says: its floor, Box2D alone replaying the random walk's
# velocities, ends with every body where the random walk's did (it prints a
# line when any is apart); every world gives a row, and a multiple taken
# against a world that did not run reads "-"; a world file it cannot read,
# or a --set its worlds refuse, fails before the table with what to do.  Not a timing: 20 robots, 20
# steps.  Usage: floor_bench.sh SWARMSIM (floor_bench beside it).  (About
# a second.)
set -u
cd "$(dirname "$0")/../.."
bench=$(cd "$(dirname "${1:-build/swarmsim}")" && pwd)/floor_bench
pass=0 fail=0
check() { if [ "$2" = "$3" ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1: '$2', expected '$3'"; fi; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$bench" --counts 20:20 --threads 1,2 --reps 1 > "$tmp/all.txt" 2> "$tmp/all.err"
check "three worlds on two thread counts: exit" "$?" 0
check "rows" "$(awk '$1 == 20 && $2 == 20' "$tmp/all.txt" | wc -l | tr -d ' ')" 6
check "no body apart from the random walk's" "$(grep -c 'apart' "$tmp/all.txt")" 0
check "the floor against itself" "$(awk '$3 == "floor" && $4 == 1 {print $8}' "$tmp/all.txt")" 1.00
check "the random walk against itself" "$(awk '$3 == "rw" && $4 == 1 {print $9}' "$tmp/all.txt")" 1.00

"$bench" --counts 20:20 --threads 1 --reps 1 --worlds fs > "$tmp/fs.txt" 2>&1
check "full sensing alone: exit" "$?" 0
check "full sensing alone: no multiple of worlds not run" "$(awk '$3 == "fs" {print $8, $9}' "$tmp/fs.txt")" "- -"

(cd "$tmp" && "$bench" --counts 20:20 --threads 1 --reps 1 > out.txt 2> err.txt)
check "outside the repository: exit" "$?" 1
check "outside the repository: nothing on stdout" "$(wc -c < "$tmp/out.txt" | tr -d ' ')" 0
check "outside the repository: says what to do" "$(grep -c "run it from the repository's root" "$tmp/err.txt")" 1

"$bench" --counts 20:20 --threads 1 --reps 1 --set ir.noise_draws=summed --set sound.noise_draws=summed \
    > "$tmp/set.txt" 2>&1
check "--set an option of both worlds: exit" "$?" 0
check "--set an option of both worlds: rows" "$(awk '$1 == 20 && $2 == 20' "$tmp/set.txt" | wc -l | tr -d ' ')" 3
"$bench" --counts 20:20 --threads 1 --reps 1 --set ir.noise_draws=each > "$tmp/bad.txt" 2> "$tmp/bad.err"
check "a bad --set: exit" "$?" 1
check "a bad --set: nothing on stdout" "$(wc -c < "$tmp/bad.txt" | tr -d ' ')" 0
check "a bad --set: names the key and the choices" \
    "$(grep -c 'ir.noise_draws: expected one of per_term|summed' "$tmp/bad.err")" 1

"$bench" --counts 20 > /dev/null 2>&1
check "a count without its steps: usage" "$?" 2
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
