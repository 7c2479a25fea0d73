#!/bin/sh
# Runs a test command with an X display for VTK's off-screen rendering (Debian's VTK renders
# through GLX; Mesa llvmpipe draws). Uses the display already there (scripts/run-tests.sh runs
# the whole ctest under one xvfb-run, so tests do not race for display numbers); otherwise
# starts a virtual one for this command alone.
if [ -n "${DISPLAY:-}" ]; then
  exec "$@"
fi
exec xvfb-run -a -s "-screen 0 1280x1024x24" "$@"
