# What every bench/extremes script starts with, sourced as
#   source "$(dirname "$0")/common.sh" "$@"
# strict mode, the repository root as the working directory ($root), the rotgen to measure
# ($rotgen: the first argument, default build/rotgen) and a scratch folder removed on exit ($work).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
root=$PWD
rotgen=$(realpath "${1:-build/rotgen}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
