#!/usr/bin/env bash
# scripts/check-includes finds what it is for: a cycle between two units of a folder (a header
# and the other unit's source including each other), a stimulus file including an app's, and an
# app including the other app's files.
set -euo pipefail
check="$(cd "$(dirname "$0")/../.." && pwd)/scripts/check-includes"
tree=$(mktemp -d)
trap 'rm -rf "$tree"' EXIT
mkdir -p "$tree/src/render" "$tree/src/adjust" "$tree/src/forced_choice" "$tree/src/stimuli" "$tree/analysis"
printf '#include "render/pass.h"\n' > "$tree/src/render/renderer.cpp"
printf '#pragma once\n' > "$tree/src/render/renderer.h"
printf '#pragma once\n#include "render/renderer.h"\n' > "$tree/src/render/pass.h"
printf '#include "render/pass.h"\n' > "$tree/src/render/pass.cpp"
printf '#include "adjust/study.h"\n' > "$tree/src/forced_choice/run.cpp"
printf '#include "adjust/study.h"\n' > "$tree/src/stimuli/experiment.cpp"
if python3 "$check" --holding "$tree" > "$tree/out"; then echo "no cycle found"; exit 1; fi
grep -q 'src/render: include cycle' "$tree/out" || { cat "$tree/out"; exit 1; }
grep -q 'src/stimuli/experiment: includes adjust/study.h' "$tree/out" || { cat "$tree/out"; exit 1; }
grep -q 'src/forced_choice/run: includes adjust/study.h' "$tree/out" || { cat "$tree/out"; exit 1; }
if python3 "$check" "$tree" > "$tree/out"; then echo "no rule broken"; exit 1; fi
grep -q 'src/forced_choice/run: includes adjust/study.h' "$tree/out" || { cat "$tree/out"; exit 1; }
rm "$tree/src/render/renderer.cpp" "$tree/src/forced_choice/run.cpp" "$tree/src/stimuli/experiment.cpp"
python3 "$check" "$tree"
echo "include check: finds the cycle and the rule, passes the tree without them"
