#!/usr/bin/env bash
# mmh-sim as a background service: sim.sh start|stop|restart|status|run [options] [-- args]
# (options and environment: see service.sh)
exec "$(dirname "$0")/service.sh" mmh-sim "$@"
