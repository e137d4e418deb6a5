#!/usr/bin/env bash
# Installs the Debian packages tcvio builds with, only those that are missing.
# As root it runs apt-get itself; otherwise it prints the exact command to run.
#   scripts/install_deps.sh               the build and the tests (gcc)
#   scripts/install_deps.sh --sanitizers  also clang, its sanitizer and
#                                         libFuzzer runtimes and llvm-symbolizer
#                                         (scripts/sanitize.sh, scripts/fuzz.sh)
set -euo pipefail

packages=(build-essential cmake libceres-dev libeigen3-dev libopencv-dev
          libyaml-cpp-dev libgtest-dev libgmock-dev libbenchmark-dev
          libboost-graph-dev lld-14)
if [ "${1:-}" = "--sanitizers" ]; then
  packages+=(clang-14 libclang-rt-14-dev llvm-14)
elif [ $# -gt 0 ]; then
  echo "install_deps: unknown option $1 (only --sanitizers)" >&2
  exit 1
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all packages present"
  exit 0
fi

cmd="apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "install_deps: missing packages: ${missing[*]}" >&2
  echo "install_deps: run as root:  sudo sh -c '$cmd'" >&2
  exit 1
fi
echo "install_deps: installing ${missing[*]}"
sh -c "$cmd"
