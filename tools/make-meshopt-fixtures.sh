#!/usr/bin/env bash
# tools/make-meshopt-fixtures.sh: rewrites tests/data/meshopt/ — two of the project's own models
# as gltfpack writes them, compressed (EXT_meshopt_compression; KHR_meshopt_compression for the
# refusal) and uncompressed for reference (libs/scene/tests/gltf_meshopt_test.cpp). Needs gltfpack
# (`npm install gltfpack`, version 1.3 made the files in the repository); the build and the tests
# never run it. pillar-cf.fallback.bin is left out on purpose: a loader that decodes needs no
# fallback.
set -euo pipefail
cd "$(dirname "$0")/.."
gltfpack=${GLTFPACK:-gltfpack}
out=tests/data/meshopt
mkdir -p "$out"
pack() { "$gltfpack" -i "$1" -o "$out/$2" "${@:3}" >/dev/null; }
pack tests/data/pillar_on_plate.gltf pillar-q.glb                # reference: quantized, uncompressed
pack tests/data/pillar_on_plate.gltf pillar-cc.glb -cc           # octahedral normals
pack tests/data/pillar_on_plate.gltf pillar-c.gltf -c            # JSON, external .bin, placeholder buffer
pack tests/data/pillar_on_plate.gltf pillar-cf.glb -cf           # fallback buffer in a file of its own
pack tests/data/pillar_on_plate.gltf pillar-khr.glb -cc -ce khr  # vertex codec version 1
pack tests/data/shapes/tree.gltf tree-q.glb                      # reference: alpha-cut cards, quantized
pack tests/data/shapes/tree.gltf tree-c.glb -c
pack tests/data/shapes/tree.gltf tree-f.glb -vpf -vtf -vnf       # reference: float attributes
pack tests/data/shapes/tree.gltf tree-exp.glb -cc -vpf -vtf -vnf # exponential filter
rm -f "$out/pillar-cf.fallback.bin"
ls -l "$out"
