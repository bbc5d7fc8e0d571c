# debian_packages.sh - sourced by the scripts that install what one test
# group needs (tools/make/browser.sh, tools/slurm/local_cluster.sh).
#
# install_debian_packages WHO CHECK PACKAGE...
#   CHECK (a function: 0 when everything is there, else it names what is
#   missing on stderr) decides; when something is missing and we are root
#   with apt-get, PACKAGE... are installed and CHECK runs again; otherwise
#   CHECK says what is missing and the line says who needs it.  Needs a
#   `say` function (one line on stderr, prefixed with the script's name).
install_debian_packages() {
    local who=$1 check=$2
    shift 2
    "$check" 2>/dev/null && return 0
    if [[ $(id -u) != 0 ]] || ! command -v apt-get >/dev/null; then
        "$check" || true
        say "cannot install them here (not root, or no apt-get): $who need them"
        return 1
    fi
    say "installing Debian packages: $*"
    export DEBIAN_FRONTEND=noninteractive
    apt-get install -y --no-install-recommends "$@" >&2 ||
        { apt-get update >&2 && apt-get install -y --no-install-recommends "$@" >&2; } || true
    "$check"
}
