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
# grove.gltf: the pillar's cube placed by 25 nodes (a plate and 24 posts, each turned and scaled
# its own way), which gltfpack -mi folds into one node of EXT_mesh_gpu_instancing.
python3 - "$out/grove.gltf" <<'PY'
import json, math, sys
sys.path.insert(0, "tools")
from authored_shapes import write_whole  # whole or not at all, a failure in one line
scene = json.load(open("tests/data/pillar_on_plate.gltf"))
nodes = [{"name": "plate", "mesh": 0, "scale": [12, 0.2, 12]}]
for i in range(24):
    angle = 2 * math.pi * i / 24
    axis = (math.sin(3 * angle), 1.0, math.cos(5 * angle))
    norm = math.sqrt(sum(a * a for a in axis))
    half = 0.5 * (0.3 + 0.25 * i)
    q = [a / norm * math.sin(half) for a in axis] + [math.cos(half)]
    nodes.append({"name": "post %d" % i, "mesh": 0,
                  "translation": [round(4.5 * math.cos(angle), 4), round(1.5 + 0.05 * i, 4), round(4.5 * math.sin(angle), 4)],
                  "rotation": [round(c, 6) for c in q],
                  "scale": [1 + 0.04 * i, 3 - 0.05 * i, 0.6 + 0.03 * i]})
scene["asset"]["generator"] = "shadowkit tools/make-meshopt-fixtures.sh"
scene["nodes"] = nodes
scene["scenes"] = [{"nodes": list(range(len(nodes)))}]
write_whole(sys.argv[1], json.dumps(scene, separators=(",", ":")))
PY
pack "$out/grove.gltf" grove-mi.glb -mi -noq                    # instancing, floats, uncompressed
pack "$out/grove.gltf" grove-mi-cc.glb -mi -cc                  # instancing, quantized, quaternion filter
pack tests/data/shapes/tree.gltf tree-q.glb                      # reference: alpha-cut cards, quantized
pack tests/data/shapes/tree.gltf tree-c.glb -c
pack tests/data/shapes/tree.gltf tree-f.glb -vpf -vtf -vnf       # reference: float attributes
pack tests/data/shapes/tree.gltf tree-exp.glb -cc -vpf -vtf -vnf # exponential filter
rm -f "$out/pillar-cf.fallback.bin"
ls -l "$out"
