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

# shellcheck source=debian_packages.sh
source "$(dirname "$0")/debian_packages.sh"
cmd_install() {
    install_debian_packages "the live view's tests" cmd_check chromium chromium-driver
}

[[ $# == 1 ]] || usage
case $1 in
check) cmd_check ;;
install) cmd_install ;;
*) usage ;;
esac
