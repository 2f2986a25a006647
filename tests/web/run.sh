#!/usr/bin/env bash
# Web suite of rbla: .3dm exchange (rhino3dm) and the browser viewer (three.js, headless Chromium).
#   RBLA_EXE=/path/to/rbla tests/web/run.sh
# Installs the pinned npm packages (npm ci, only when node_modules is missing or stale), builds the
# viewer, makes sure Debian's chromium is there (apt-get when root; otherwise the viewer tests are
# skipped with a message), then runs `node --test tests/web/*.test.mjs`.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
export npm_config_fund=false npm_config_audit=false npm_config_update_notifier=false

# exit 77 = skipped (CTest SKIP_RETURN_CODE) when Node or npm is missing
command -v node >/dev/null || { echo "web tests: SKIPPED, node not found (apt-get install -y nodejs npm)" >&2; exit 77; }
command -v npm >/dev/null || { echo "web tests: SKIPPED, npm not found (apt-get install -y npm)" >&2; exit 77; }

# --- rbla binary -----------------------------------------------------------------------------------
if [[ -z "${RBLA_EXE:-}" ]]; then
  for c in "$REPO/build-web/solver/rbla" "$REPO/build/solver/rbla"; do
    [[ -x "$c" ]] && { RBLA_EXE="$c"; break; }
  done
fi
if [[ -z "${RBLA_EXE:-}" || ! -x "$RBLA_EXE" ]]; then
  echo "web tests: rbla binary not found; set RBLA_EXE=/path/to/rbla" >&2
  exit 1
fi
export RBLA_EXE

# --- npm packages (pinned by package-lock.json) -------------------------------------------------------
install_pkgs() {
  local dir="$1"
  if [[ -f "$dir/node_modules/.package-lock.json" && "$dir/node_modules/.package-lock.json" -nt "$dir/package-lock.json" ]]; then
    return 0
  fi
  echo "web tests: npm ci in ${dir#$REPO/}"
  (cd "$dir" && npm ci --prefer-offline --no-audit --no-fund --loglevel=error)
}
install_pkgs "$REPO/plugin/exchange"
install_pkgs "$REPO/plugin/viewer"
install_pkgs "$REPO/tests/web"
(cd "$REPO/plugin/viewer" && npm run --silent build >/dev/null)

# --- chromium ---------------------------------------------------------------------------------------
CHROMIUM="${RBLA_CHROMIUM:-/usr/bin/chromium}"
if [[ ! -x "$CHROMIUM" ]]; then
  if [[ "$(id -u)" == 0 ]] && command -v apt-get >/dev/null; then
    echo "web tests: installing Debian's chromium"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null 2>&1 \
      || { apt-get update -q >/dev/null 2>&1 && DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null 2>&1; } \
      || true
  fi
  if [[ ! -x "$CHROMIUM" ]]; then
    echo "web tests: chromium not available at $CHROMIUM and could not be installed: the viewer tests will be SKIPPED" >&2
  fi
fi
export RBLA_CHROMIUM="$CHROMIUM"

cd "$REPO"
# explicit file list (newer Node versions read positional arguments as globs, not directories)
exec node --test --test-timeout=120000 tests/web/*.test.mjs
