#!/usr/bin/env bash
# The layer check can fail: a copy of the headers where core/joint.hpp
# includes a dynamics header must be refused, naming the include.
set -euo pipefail
src=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r "$src/include/flange" "$work/flange"
echo '#include "flange/dynamics/links.hpp"' >> "$work/flange/core/joint.hpp"
if out=$("$src/tools/check_layers.sh" "$work/flange" 2>&1); then
  echo "the layer check accepted an include that points up"
  exit 1
fi
grep -q "core/joint.hpp (layer 2) includes flange/dynamics/links.hpp (layer 6)" <<<"$out"
echo "refused as expected: $out"
