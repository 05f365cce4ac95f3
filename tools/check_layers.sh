#!/usr/bin/env bash
# Fails when a header includes one from a higher layer (docs/architecture.md):
#   0 detail/, errors.hpp   1 math/   2 core/   3 components/, joints/, forces/
#   4 scene/   5 equations/   6 dynamics/   7 simulate/   8 models/, study/, ensemble/, viewer/   9 flange.hpp
#   10 python/
# A header may include its own layer and the layers below it.
#   tools/check_layers.sh [include/flange]
set -euo pipefail
root=${1:-include/flange}
rank() {
  case "$1" in
    detail/*|errors.hpp) echo 0 ;;
    math/*) echo 1 ;;
    core/*) echo 2 ;;
    components/*|joints/*|forces/*) echo 3 ;;
    scene/*) echo 4 ;;
    equations/*) echo 5 ;;
    dynamics/*) echo 6 ;;
    simulate/*) echo 7 ;;
    models/*|study/*|ensemble/*|viewer/*) echo 8 ;;
    flange.hpp|equations_of_motion.hpp) echo 9 ;;
    python/*) echo 10 ;;
    *) echo "unknown" ;;
  esac
}
bad=0
while IFS= read -r file; do
  rel=${file#"$root"/}
  r=$(rank "$rel")
  if [[ $r == unknown ]]; then
    echo "check_layers: $rel is in no layer; add its folder to tools/check_layers.sh and docs/architecture.md"
    bad=1
    continue
  fi
  while IFS= read -r inc; do
    t=$(rank "$inc")
    if [[ $t == unknown || $t -gt $r ]]; then
      echo "check_layers: $rel (layer $r) includes flange/$inc (layer $t), which points up"
      bad=1
    fi
  done < <(grep -oE '#include "flange/[^"]+"' "$file" | sed 's/#include "flange\///; s/"//')
done < <(find "$root" -name '*.hpp' -o -name '*.h' | sort)
if ((bad)); then exit 1; fi
echo "check_layers: every include points down or sideways ($(find "$root" -name '*.hpp' -o -name '*.h' | wc -l) headers)"
