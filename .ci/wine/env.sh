# Sourced by .ci/wine/setup and .ci/wine/run: where Wine is and which prefix we use.
# The prefix lives under target/ (never committed, removed by cargo clean) unless
# WINEPREFIX is set.
WINE_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export WINEPREFIX="${WINEPREFIX:-$WINE_ROOT/target/wine}"
# Wine's own chatter (fixme:, err: about a missing display) is not our output.
export WINEDEBUG="${WINEDEBUG:--all}"
# A console program needs no display; keep Wine from looking for one.
unset DISPLAY WAYLAND_DISPLAY
# Debian's wine64 package installs no `wine` on PATH, only /usr/lib/wine/wine64.
WINE="$(command -v wine64 || command -v wine || echo /usr/lib/wine/wine64)"
