# Sourced by the command-line test scripts: SCRIPT CASE SHARPMESH_BINARY DATA_DIR.
# Runs the case in a fresh scratch folder, removed on exit (even a read-only one).
set -uo pipefail
case_name=$1 bin=$2 data=$3
work=$(mktemp -d)
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
cd "$work" || exit 1

fail() { echo "FAIL [$case_name]: $*" >&2; exit 1; }
