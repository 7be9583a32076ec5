#!/usr/bin/env bash
# Install everything vpt needs on a fresh Debian/Ubuntu machine: Chromium (for headless
# rendering and the browser tests), pnpm (pinned in package.json), the workspace's
# packages; then build every package (`pnpm test` and `pnpm demo` build again, quickly).
set -euo pipefail

# No options: --help says what this does, anything else is refused (before any install).
case "${1-}" in
  "") ;;
  -h | --help)
    echo "Usage: scripts/setup.sh"
    echo "Installs Chromium (apt-get, unless VPT_CHROMIUM, CHROMIUM_PATH or /usr/bin/chromium is there),"
    echo "pnpm (the version package.json pins, with npm) and the workspace's packages (pnpm install)."
    exit 0
    ;;
  *)
    echo "setup.sh: unknown argument '$1' (it takes none; --help says what it does)" >&2
    exit 2
    ;;
esac
cd "$(dirname "$0")/.."

# Node.js >= 20 (package.json engines; CI runs 20.20). puppeteer-core 25 declares >= 22.12,
# but the part of it vpt uses (launching Chromium over a pipe) runs on 20 and is tested there.
if ! node -e 'process.exit(Number(process.versions.node.split(".")[0]) >= 20 ? 0 : 1)'; then
  echo "setup: Node.js $(node --version) is too old; vpt needs Node.js >= 20" >&2
  exit 1
fi

if [ -z "${VPT_CHROMIUM:-}" ] && [ -z "${CHROMIUM_PATH:-}" ] && [ ! -x /usr/bin/chromium ]; then
  echo "setup: installing Chromium (apt-get)"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium > /dev/null
fi

want_pnpm="$(node -p "require('./package.json').packageManager.split('@')[1]")"
if ! command -v pnpm > /dev/null || [ "$(pnpm --version)" != "$want_pnpm" ]; then
  echo "setup: installing pnpm@$want_pnpm (npm)"
  npm install -g "pnpm@$want_pnpm" > /dev/null
fi

pnpm install --frozen-lockfile
echo "setup: building every package (pnpm run build)"
pnpm run build > /dev/null
echo "setup: done; try pnpm demo or pnpm render apps/gallery/scenes/head-eam.json -o out/head.png"
