#!/usr/bin/env bash
# mmh-setpoint (the trajectory server: TRAJECTORY -> SETPOINT for a flight controller) as a
# background service: setpoint.sh start|stop|restart|status|run [options] [-- args]
# (options and environment: see service.sh)
exec "$(dirname "$0")/service.sh" mmh-setpoint "$@"
