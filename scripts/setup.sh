#!/usr/bin/env bash
# Install everything vpt needs on a fresh Debian/Ubuntu machine: Chromium (for headless
# rendering and the browser tests), pnpm (pinned in package.json), the workspace's
# packages; then build every package (`pnpm test` and `pnpm demo` build again, quickly).
set -euo pipefail
cd "$(dirname "$0")/.."

# Node.js >= 22.12: puppeteer-core 25, which drives Chromium, requires it (package.json engines).
if ! node -e 'const [a, b] = process.versions.node.split(".").map(Number); process.exit(a > 22 || (a === 22 && b >= 12) ? 0 : 1)'; then
  echo "setup: Node.js $(node --version) is too old; vpt needs Node.js >= 22.12 (puppeteer-core 25 requires it)" >&2
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
