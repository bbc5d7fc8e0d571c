#!/usr/bin/env bash
# code_version.sh - the code version every output records
# (tools/make/code_version.sh) tells a clean commit from its edits: a clean
# checkout gives git describe; a tracked file's uncommitted change adds
# "-dirty-" and the diff's hash, the same for the same edit and another for
# another; outside git it is "unknown".  In a throw-away repository.  Usage:
# code_version.sh [SWARMSIM] (not used).  (Under a second.)
set -u
cd "$(dirname "$0")/../.."
script=$PWD/tools/make/code_version.sh
pass=0 fail=0
check() { if [ "$2" = "$3" ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1: '$2', expected '$3'"; fi; }
like() { if [[ $2 =~ $3 ]]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1: '$2' is not $3"; fi; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
git -C "$tmp" init -q && git -C "$tmp" -c user.name=t -c user.email=t@t commit -q --allow-empty -m base
echo one > "$tmp/f" && git -C "$tmp" add f && git -C "$tmp" -c user.name=t -c user.email=t@t commit -q -m f
clean=$(bash "$script" "$tmp")
check "a clean checkout" "$clean" "$(git -C "$tmp" describe --always --dirty --abbrev=12)"
echo two > "$tmp/f"
edit1=$(bash "$script" "$tmp")
like "an edited tracked file" "$edit1" "^$clean-dirty-[0-9a-f]{12}$"
check "the same edit again" "$(bash "$script" "$tmp")" "$edit1"
echo three > "$tmp/f"
edit2=$(bash "$script" "$tmp")
like "another edit" "$edit2" "^$clean-dirty-[0-9a-f]{12}$"
if [ "$edit1" != "$edit2" ]; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: two edits gave one version $edit1"; fi
echo one > "$tmp/f"
check "the edit undone" "$(bash "$script" "$tmp")" "$clean"
mkdir "$tmp/notgit"
check "outside git" "$(GIT_CEILING_DIRECTORIES=$tmp bash "$script" "$tmp/notgit")" unknown
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
