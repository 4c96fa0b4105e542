#!/usr/bin/env bash
# make deps — install the Debian packages lozenge needs, only those missing.
# As root it installs them; otherwise it prints the one apt-get line to run.
set -euo pipefail

packages=(libgsl-dev check gnuplot-nox libopenmpi-dev openmpi-bin pkg-config pandoc)

# What each package provides, tested directly, so another distribution's or a
# hand-built install also counts.
have() {
	case "$1" in
	libgsl-dev) pkg-config --exists gsl 2>/dev/null ;;
	check) pkg-config --exists check 2>/dev/null ;;
	gnuplot-nox) command -v gnuplot >/dev/null ;;
	libopenmpi-dev) command -v mpicc >/dev/null ;;
	openmpi-bin) command -v mpirun >/dev/null ;;
	pkg-config) command -v pkg-config >/dev/null ;;
	pandoc) command -v pandoc >/dev/null ;;
	esac
}

missing=()
for p in "${packages[@]}"; do
	have "$p" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
	echo "deps: all present (${packages[*]})"
	exit 0
fi

if ! command -v apt-get >/dev/null; then
	echo "deps: missing ${missing[*]}; this is not a Debian system: install GSL, Check," \
	     "gnuplot, OpenMPI, pkg-config and pandoc with your package manager" >&2
	exit 1
fi
if [ "$(id -u)" -ne 0 ]; then
	echo "deps: missing ${missing[*]}. Run:" >&2
	echo "  sudo apt-get install -y ${missing[*]}" >&2
	exit 1
fi
echo "deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
for p in "${missing[@]}"; do
	have "$p" || { echo "deps: $p did not install" >&2; exit 1; }
done
echo "deps: done"
