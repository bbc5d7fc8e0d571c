#!/usr/bin/env bash
# defaults_documented.sh - every default the documents state (the params and
# config structs' comments, the README's and docs/' key tables) is the one
# the descriptors give (swarmsim --help): defaults_documented.py.  (A second.)
set -u
sim=${1:-build/swarmsim}
case $sim in /*) ;; *) sim="$PWD/$sim" ;; esac
cd "$(dirname "$0")/../.." || exit 1
python3 tests/cli/defaults_documented.py "$sim"
