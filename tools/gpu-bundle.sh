#!/usr/bin/env bash
# tools/gpu-bundle.sh: packs what tools/measure-gpu.sh needs on a machine that has an NVIDIA driver
# with EGL but none of this project's Debian libraries (docs/performance.md "On a real GPU") into
# .gpu/bundle.tar.xz: the `shadowkit` CLI, the GL test programs and every shared library they load
# except the C and C++ runtimes (the target's are newer). Embree alone is 44 MB; xz packs the lot to
# about a fifth (~12 MB), small enough to copy anywhere.
# The GL loader (Debian's libglvnd, libepoxy and libegl packages, as .deb files in .gl/) is copied
# beside it when the GPU machine has none: `apt-get download` them here.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/bin" "$stage/lib" .gpu
programs=(build/apps/shadowkit/shadowkit build/libs/gl/shadowkit_gl_tests build/libs/frame/shadowkit_frame_tests
          build/tests/shadowkit_integration_tests build/tests/shadowkit_golden_tests)
cp "${programs[@]}" "$stage/bin/"
# The libraries the programs load, minus glibc's, libgcc's and libstdc++'s.
ldd "${programs[@]}" | awk '$3 ~ /^\// {print $3}' | sort -u |
  grep -Ev '/(libc|libm|libdl|libpthread|librt|libgcc_s|libstdc\+\+|ld-linux[^/]*)\.so' |
  while read -r lib; do cp -L "$lib" "$stage/lib/"; done
tar -C "$stage" -cJf .gpu/bundle.tar.xz bin lib
git rev-parse --short HEAD >.gpu/commit
echo "packed $(ls "$stage/lib" | wc -l) libraries and ${#programs[@]} programs of $(cat .gpu/commit): $(du -h .gpu/bundle.tar.xz | cut -f1)"
