#!/usr/bin/env bash
# mmh-goal as a background service (repeats the mission goal at 1 Hz until stopped):
# goal.sh start|stop|status [options] -- --goal x,y,z [--id N]   (options: see service.sh)
exec "$(dirname "$0")/service.sh" mmh-goal "$@"
