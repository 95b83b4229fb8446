#!/usr/bin/env bash
# Stimuli are the same bytes on every x86-64 processor: this machine's, an AVX2 one without
# AVX-512 (QEMU's Haswell) and a baseline one without AVX (QEMU's qemu64). Embree, the vectorised
# colour code and the Gaussian each pick their code path by the processor at run time.
#   same_bytes_on_other_processors.sh COUNTERSHADE_BINARY
set -euo pipefail
binary=$1
command -v qemu-x86_64 > /dev/null || { echo "qemu-x86_64 is missing (scripts/setup installs qemu-user)"; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Curved and tilted triangles in every direction, cast shadows, sky light and a mip-mapped texture:
# every hit's distance, barycentrics and footprint, and every colour path, matter.
cat > "$out/scene.json" <<'JSON'
{"version": 1,
 "camera": {"eye": [2.2, 1.6, 3.0], "target": [0, 0.4, 0], "fov": 38, "width": 40, "height": 30},
 "render": {"seed": 3},
 "objects": [
   {"name": "floor", "shape": {"type": "plane", "size": 6, "subdivisions": 8},
    "material": {"texture": {"pattern": "checker-noise", "size": 64, "squares": 4, "noise": 0.35, "seed": 2},
                 "texture_repeat": 3}},
   {"name": "ball", "shape": {"type": "sphere", "radius": 0.5, "subdivisions": 2},
    "transform": {"translate": [-0.5, 0.5, 0]}, "material": {"albedo": [0.7, 0.5, 0.4]}},
   {"name": "box", "shape": {"type": "box", "size": [0.6, 0.9, 0.6]},
    "transform": {"rotate": [10, 35, 0], "translate": [0.6, 0.45, -0.2]}}],
 "lights": [{"type": "directional", "direction": [0.5, 1, 0.3], "irradiance": 2.2},
            {"type": "environment", "constant": [0.3, 0.32, 0.36], "samples": 2}]}
JSON

render() {  # CPU NAME ARGS...: native runs without QEMU
  local cpu=$1 name=$2
  shift 2
  local run=("$binary")
  [ "$cpu" = native ] || run=(qemu-x86_64 -cpu "$cpu" "$binary")
  "${run[@]}" render "$out/scene.json" --spp 4 -o "$out/$cpu-$name.png" "$@" > "$out/$cpu-$name.log" 2>&1 ||
    { cat "$out/$cpu-$name.log"; exit 1; }
}

failed=0
for cpu in native Haswell-v4 qemu64; do
  render "$cpu" plain --aux "$out/$cpu-aux"
  render "$cpu" usm3d --method usm3d --sigma 0.15 --lambda 2
  render "$cpu" usm2d --method usm2d --sigma-px 2 --lambda 2
  render "$cpu" depth-usm --method depth-usm --kernel 10 --lambda 1
  render "$cpu" texture-filter --method texture-filter --mode mip --filter unsharp --sigma 2 --lambda 1
  render "$cpu" lla --method lla --sigma 0.05 --lambda 1
  [ "$cpu" = native ] && continue
  # The G-buffer holds each hit's depth and interpolated normal as floats: a difference in the
  # last bits shows there even where no 8-bit code changes.
  for aux in depth normal; do
    if ! idiff -fail 0 -warn 0 "$out/native-aux/$aux.exr" "$out/$cpu-aux/$aux.exr" > "$out/idiff.log" 2>&1; then
      echo "$aux.exr: the G-buffer on $cpu differs from this processor's: $(grep -m1 'Max error' "$out/idiff.log")"
      failed=1
    fi
  done
  for name in plain usm3d usm2d depth-usm texture-filter lla; do
    if ! cmp -s "$out/native-$name.png" "$out/$cpu-$name.png"; then
      echo "$name: the image on $cpu differs from this processor's"
      failed=1
    fi
  done
done
[ "$failed" = 0 ] && echo "the same bytes on this processor, Haswell-v4 and qemu64 (plain, usm3d, usm2d, depth-usm, texture-filter, lla, G-buffer)"
exit "$failed"
