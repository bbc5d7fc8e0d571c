#!/usr/bin/env bash
# code_version.sh [DIR] - the code version every output records (swarmsim's
# summaries through build/gen/version.h, the sweep engine's tables): git
# describe of the checkout DIR (default this repository), with 12 hex
# digits of the commit, and when tracked files have uncommitted changes
# "-dirty-" and 12 hex digits of the SHA-256 of `git diff HEAD`, so that two
# different edits of one commit are told apart; "unknown" outside git.
cd "${1:-$(dirname "$0")/../..}" 2>/dev/null || { echo unknown; exit 0; }
v=$(git describe --always --dirty --abbrev=12 2>/dev/null) || { echo unknown; exit 0; }
case $v in
    *-dirty) v="$v-$(git diff HEAD --binary 2>/dev/null | sha256sum | cut -c1-12)" ;;
esac
echo "$v"
