#!/usr/bin/env bash
# browser.sh - Debian's chromium and chromium-driver, the real headless
# browser of the live view's tests (make live-tests, tools/tests/live/).
#
#   browser.sh check     are /usr/bin/chromium and /usr/bin/chromedriver there?
#                        (else: which packages, status 1)
#   browser.sh install   install the missing packages with apt-get (as root),
#                        or say which and why not, status 1
#
# The tests name both programs to Selenium, so nothing else ever fetches a
# browser or a driver.
set -euo pipefail

PROG=browser
say() { echo "$PROG: $*" >&2; }

# program : Debian package providing it
PROGRAMS=(/usr/bin/chromium:chromium /usr/bin/chromedriver:chromium-driver)

usage() {
    echo "usage: $0 check | install" >&2
    exit 2
}

cmd_check() {
    local p prog pkg missing=()
    for p in "${PROGRAMS[@]}"; do
        prog=${p%%:*} pkg=${p#*:}
        [[ -x $prog ]] || missing+=("$pkg")
    done
    if ((${#missing[@]})); then
        say "missing: ${missing[*]} (the live view's tests drive /usr/bin/chromium through /usr/bin/chromedriver)"
        say "install them with: apt-get install -y --no-install-recommends ${missing[*]}"
        return 1
    fi
    return 0
}

cmd_install() {
    cmd_check 2>/dev/null && return 0
    if [[ $(id -u) != 0 ]] || ! command -v apt-get >/dev/null; then
        cmd_check || true
        say "cannot install them here (not root, or no apt-get): the live view's tests need them"
        return 1
    fi
    local pkgs=(chromium chromium-driver)
    say "installing Debian packages: ${pkgs[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get install -y --no-install-recommends "${pkgs[@]}" >&2 ||
        { apt-get update >&2 && apt-get install -y --no-install-recommends "${pkgs[@]}" >&2; } || true
    cmd_check
}

[[ $# == 1 ]] || usage
case $1 in
check) cmd_check ;;
install) cmd_install ;;
*) usage ;;
esac
