#!/usr/bin/env bash
# Fails when a file of a lower layer includes a header of a higher one.
#
#   bash tests/checks/layering.sh SOURCE_DIR
#
# The layers, lowest first (a layer may include its own headers and those of any layer below):
#
#   geometry < io < volume < dynamics < validation < formats < report < cli
#
#   geometry    meshes, primitives, poses, bounding-volume trees, broad phase
#   io          low-level readers and plain writers: meshes, shape and pose text, JSON files
#   volume      the interference volume of two shapes (ContactVolume), one backend per method
#   dynamics    the force model (effects), contact-pair state, rigid bodies, integration
#   validation  datasets, replay, residuals, fitting, diagnosis, reference experiments
#   formats     documents that build engine objects: scenario, model and dataset files
#   report      what the engine writes for a reader: CSV tables, result JSON, the HTML report
#   cli         the vcontact command: option parsing and printing
#
# tests/ and benchmarks/ may include any layer.
#
# Above volume/, only its public headers may be included: the contact volume type and the query
# (volume/contact_volume.hpp, volume/contact.hpp); the methods' folders, the method table and the
# shared kernels are volume's own (a recovered surface is opaque above volume/: made and
# described through the query header, queried through the method table's `recovered` row).
set -euo pipefail
src="${1:?usage: layering.sh SOURCE_DIR}"
layers=(geometry io volume dynamics validation formats report cli)
declare -A rank
for i in "${!layers[@]}"; do rank[${layers[$i]}]=$i; done

order=$(printf ' < %s' "${layers[@]}")
order=${order:3}
public_volume=(volume/contact_volume.hpp volume/contact.hpp)
violations=0
for layer in "${layers[@]}"; do
  [ -d "$src/$layer" ] || continue
  while IFS= read -r hit; do
    file=${hit%%:*}
    rest=${hit#*:}
    line=${rest%%:*}
    included=${rest#*\"}
    included=${included%%/*}
    [ -n "${rank[$included]:-}" ] || continue
    if ((rank[$included] > rank[$layer])); then
      echo "${file#"$src"/}:$line: $layer/ must not include $included/ (layers, lowest first: $order)"
      violations=$((violations + 1))
    elif [ "$included" = volume ] && ((rank[$layer] > rank[volume])); then
      header=${rest#*\"}
      header=${header%%\"*}
      if [[ " ${public_volume[*]} " != *" $header "* ]]; then
        echo "${file#"$src"/}:$line: $layer/ must not include $header, internal to volume/ (public: ${public_volume[*]})"
        violations=$((violations + 1))
      fi
    fi
  done < <(grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[a-z_]+/' \
    --include='*.hpp' --include='*.cpp' "$src/$layer" || true)
done
if ((violations)); then
  echo "layering: $violations include(s) of a higher layer or of a header internal to volume/" >&2
  exit 1
fi
echo "layering: every include points at the same or a lower layer ($order), and above volume/ at its public headers only"
