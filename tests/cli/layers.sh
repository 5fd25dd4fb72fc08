#!/usr/bin/env bash
# Usage: layers.sh SOURCE_DIR
#
# The layers of doc/design.md, Section 5: a folder of include/rbc_ifem/ and
# source/ includes headers of its own folder and of the folders before it in
#   base geometry fluid membrane coupling diffusion ifem experiments
# only; the root parameters.h, which gathers the parameters up to ifem/,
# counts as ifem/; reference/ includes only base/. Lists every include that
# breaks this and fails.
set -u
cd "$1" || exit 1
layers=(base geometry fluid membrane coupling diffusion ifem experiments)
rank() { # the position of a folder in the layers, or "" for none
  local i
  for i in "${!layers[@]}"; do [ "${layers[$i]}" = "$1" ] && echo "$i" && return; done
}
failed=0
checked=0
while IFS= read -r file; do
  folder=$(echo "$file" | sed -E 's|^(include/rbc_ifem\|source)/||; s|/.*||')
  [[ $folder == *.* ]] && folder=ifem # include/rbc_ifem/parameters.h, source/parameters.cc
  while IFS= read -r header; do
    target=${header%%/*}
    [[ $target == *.h ]] && target=ifem
    checked=$((checked + 1))
    if [ "$folder" = reference ]; then
      ok=$([ "$target" = base ] || [ "$target" = reference ] && echo yes)
    else
      ok=$([ -n "$(rank "$target")" ] && [ "$(rank "$target")" -le "$(rank "$folder")" ] && echo yes)
    fi
    if [ "$ok" != yes ]; then
      echo "FAILED: $file includes rbc_ifem/$header ($folder/ may not use $target/)"
      failed=1
    fi
  done < <(sed -n 's|^ *# *include <rbc_ifem/\(.*\)>.*|\1|p' "$file")
done < <(find include/rbc_ifem source -name '*.h' -o -name '*.cc' | sort)
[ $failed -eq 0 ] && echo "ok: $checked includes follow the layers"
exit $failed
