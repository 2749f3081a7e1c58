#!/bin/sh
# compare_objects.sh OLD_TREE NEW_TREE — the machine code of the runtime's
# objects in two built trees (build/rt/, flat or in rooms), object by object
# by file name: "same" when the .text sections are byte-identical, "differs"
# with their sizes, "new" or "gone".  A refactor that moves code between files
# shows here which kernels it left untouched to the byte, beside
# compare_outputs.sh, which shows that the outputs are.
set -u
old=$1 new=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
text() { objcopy -O binary --only-section=.text "$1" "$2" 2>/dev/null || : >"$2"; }
find "$old/build/rt" -name '*.o' | sort >"$tmp/old"
find "$new/build/rt" -name '*.o' | sort >"$tmp/new"
while read -r o; do
  name=$(basename "$o")
  b=$(grep "/$name\$" "$tmp/old" | head -1)
  if [ -z "$b" ]; then echo "new      $name"; continue; fi
  text "$b" "$tmp/a"; text "$o" "$tmp/b"
  if cmp -s "$tmp/a" "$tmp/b"; then echo "same     $name"
  else echo "differs  $name ($(wc -c <"$tmp/a") -> $(wc -c <"$tmp/b") bytes of .text)"; fi
done <"$tmp/new"
while read -r b; do
  name=$(basename "$b")
  grep -q "/$name\$" "$tmp/new" || echo "gone     $name"
done <"$tmp/old"
