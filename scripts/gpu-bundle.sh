#!/usr/bin/env bash
# Packs what scripts/gpu-check.sh needs on a machine that has a GPU but neither this project's
# packages nor a network: build/repose, the engine tests, vulkaninfo, and every shared library they
# load apart from the C library itself, into one folder (default .gpu-bundle, ignored by git).
# Usage: bash scripts/gpu-bundle.sh [DIR]      (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-.gpu-bundle}
rm -rf "$dir"
mkdir -p "$dir/bin" "$dir/lib"
cp build/repose build/test_engine "$dir/bin/"
command -v vulkaninfo >/dev/null && cp "$(command -v vulkaninfo)" "$dir/bin/"
for exe in "$dir"/bin/*; do
  ldd "$exe" | awk '$3 ~ /^\// {print $3}'
done | sort -u | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*) ;;  # the machine's own glibc
    *) cp -L "$lib" "$dir/lib/" ;;
  esac
done
# The NVIDIA Vulkan driver loads glvnd's libraries, which a bare CUDA image may lack: without them
# (libEGL too: a bundle without it failed again), such a machine answered "no Vulkan driver found"
# (2026-11-27, an H200).
glvnd=()
for pkg in libglvnd0 libglx0 libegl1; do dpkg -s "$pkg" >/dev/null 2>&1 || glvnd+=("$pkg"); done
if [ ${#glvnd[@]} -gt 0 ]; then
  apt-get update -qq && apt-get install -y -qq --no-install-recommends "${glvnd[@]}"
fi
for lib in libGLdispatch.so.0 libGLX.so.0 libEGL.so.1; do
  cp -L "/usr/lib/x86_64-linux-gnu/$lib" "$dir/lib/"
done
# The tests find their cases under the source folder compiled into them, and run the binary
# whose path is compiled into them.
flags=build/CMakeFiles/test_engine.dir/flags.make
grep -o 'REPOSE_SOURCE_DIR=[^ ]*' $flags | head -1 | cut -d= -f2- | tr -d '"\\' > "$dir/source_dir"
grep -o 'REPOSE_BINARY=[^ ]*' $flags | head -1 | cut -d= -f2- | tr -d '"\\' > "$dir/binary_path"
du -sh "$dir"
