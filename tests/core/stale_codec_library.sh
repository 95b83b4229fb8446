#!/usr/bin/env bash
# A codec library left from another build beside the program (a partial upgrade, a copied binary)
# is refused with a line that names it, and the command fails cleanly: no crash, no output file.
set -euo pipefail
binary=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cp "$binary" "$out/countershade"
# The stale library's entry point returns an object no program could use: calling it would crash.
cat > "$out/stale.c" <<'C'
const char* countershade_plugin_interface(void) { return "0123456789abcdef"; }
void* countershade_png_codec(void) { return (void*)16; }
C
cc -shared -fPIC -o "$out/libcountershade_png_codec.so" "$out/stale.c"
# A 2×2 grey image (PFM: little-endian floats of 0.5).
{ printf 'Pf\n2 2\n-1.0\n'; printf '\x00\x00\x00\x3f%.0s' 1 2 3 4; } > "$out/grey.pfm"

status=0
"$out/countershade" image-usm "$out/grey.pfm" -o "$out/out.png" --method usm2d --sigma-px 1 \
  > "$out/log" 2>&1 || status=$?
if [ "$status" -eq 0 ] || [ "$status" -ge 128 ]; then
  echo "expected a clean failure, got exit status $status:"; cat "$out/log"; exit 1
fi
if ! grep -q "libcountershade_png_codec.so: built for another version of countershade" "$out/log"; then
  echo "the error does not name the stale library:"; cat "$out/log"; exit 1
fi
if [ -e "$out/out.png" ]; then echo "an output file was written"; exit 1; fi
echo "refused: $(tail -n 1 "$out/log")"
